// SPDX-License-Identifier: MIT
// Chipmunk2D 7 (chipmunk_ref/) behind the Engine interface: a second reference engine.
#include "chipmunk_ref/chipmunk_world.h"
#include "engines/registry.h"

namespace chainbench {
namespace {

const std::vector<CounterDef>& counter_list() {
  static const std::vector<CounterDef> list = {
      {"contacts", Aggregate::kMean, "touching pairs after each step, sleeping ones included", ""}};
  return list;
}

ChipmunkSettings settings(const EngineSpec& spec) {
  ChipmunkSettings s;
  s.iterations = static_cast<int>(spec.get_int("iterations"));
  s.substeps = static_cast<int>(spec.get_int("substeps"));
  s.slop = spec.get_number("slop");
  s.bias = spec.get_number("bias");
  s.compensate_skin = spec.get("skin") == "compensate";
  s.sleep = spec.get_int("sleep") != 0;
  return s;
}

class ChipmunkEngine final : public Engine {
 public:
  ChipmunkEngine(const EngineSpec& spec, const Scene& scene) : world_(scene, settings(spec)) {}
  void step(int step_index) override { world_.step(step_index); }
  void add_body(std::size_t index) override { world_.add_body(index); }
  void remove_body(std::size_t index) override { world_.remove_body(index); }
  void read_state(BodyState& out) const override {
    world_.read_state(out.position, out.velocity, out.angle);
  }
  // Counted here, outside the timed step.
  std::span<const CounterDef> counter_defs() const override { return counter_list(); }
  std::span<const double> counters() const override {
    contacts_ = static_cast<double>(world_.touching_pairs());
    return {&contacts_, 1};
  }

 private:
  ChipmunkWorld world_;
  mutable double contacts_ = 0.0;
};

}  // namespace

EngineDef register_chipmunk() {
  EngineDef e;
  e.name = "chipmunk";
  e.description = "Chipmunk2D 7 (Debian libchipmunk), fixed rotation unless the scene rotates";
  e.keys = {
      whole_key("iterations", 10, 1, 1000, "solver iterations per step"),
      whole_key("substeps", 1, 1, 1000, "space steps per scene step"),
      number_key("slop", 0.005, 0.0, 1.0, "overlap contacts may keep, m (Chipmunk's own: 0.1)"),
      number_key("bias", ChipmunkSettings{}.bias, 0.0, 1.0,
                 "share of an overlap left after one second of correction"),
      choice_key("skin", "compensate", {"compensate", "raw"},
                 "compensate: shapes built slop/2 larger per side so boxes rest at their faces"),
      whole_key("sleep", 0, 0, 1, "bodies at rest fall asleep, as games ship it")};
  e.capabilities = [](const EngineSpec&) {
    return Capabilities{true, true, true, true, true, true, true, true};
  };
  e.counters = counter_list();
  e.caveat =
      "Debian's Chipmunk 7 is built with its debug checks on, so its times overstate what a "
      "release build of Chipmunk costs";
  e.defaults = {"chipmunk"};
  e.accurate = "chipmunk:iterations=40,substeps=8";
  e.sweep = {"iterations=2,5,20,40", "substeps=2,4,8", "skin=raw"};
  // Beyond about 30,000 bodies a step of Debian's build takes most of a second (0.9 s on 137,550
  // resting boxes), and with sleeping on, a step in which many bodies fall asleep takes seconds.
  e.benchmarks = {{"chipmunk", 30'000}, {"chipmunk:sleep=1", 30'000}};
  e.make = [](const EngineSpec& spec, const Scene& scene) -> std::unique_ptr<Engine> {
    return std::make_unique<ChipmunkEngine>(spec, scene);
  };
  return e;
}

}  // namespace chainbench
