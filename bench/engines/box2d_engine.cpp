// SPDX-License-Identifier: MIT
// Box2D 2.4 (box2d_ref/) behind the Engine interface.
#include "box2d_ref/box2d_world.h"
#include "engines/registry.h"

#include <array>

namespace chainbench {
namespace {

const std::vector<CounterDef>& counter_list() {
  static const std::vector<CounterDef> list = {
      {"contacts", Aggregate::kMean, "touching contacts after each step, sleeping ones included",
       ""}};
  return list;
}

Box2dSettings settings(const EngineSpec& spec) {
  Box2dSettings s;
  s.velocity_iterations = static_cast<int>(spec.get_int("vel_iters"));
  s.position_iterations = static_cast<int>(spec.get_int("pos_iters"));
  s.substeps = static_cast<int>(spec.get_int("substeps"));
  s.compensate_skin = spec.get("skin") == "compensate";
  s.warm_starting = spec.get_int("warm") != 0;
  s.continuous = static_cast<int>(spec.get_int("ccd"));
  s.sleep = spec.get_int("sleep") != 0;
  return s;
}

class Box2dEngine final : public Engine {
 public:
  Box2dEngine(const EngineSpec& spec, const Scene& scene) : world_(scene, settings(spec)) {}
  void step(int step_index) override { world_.step(step_index); }
  void add_body(std::size_t index) override { world_.add_body(index); }
  void remove_body(std::size_t index) override { world_.remove_body(index); }
  void read_state(BodyState& out) const override {
    world_.read_state(out.position, out.velocity, out.angle);
  }
  // Counted here, outside the timed step.
  std::span<const CounterDef> counter_defs() const override { return counter_list(); }
  std::span<const double> counters() const override {
    contacts_ = static_cast<double>(world_.touching_contacts());
    return {&contacts_, 1};
  }
  // Box2D times its stages whether asked or not.
  void measure_stages() override { profiling_ = true; }
  std::span<const StageTime> stages() const override {
    if (!profiling_) return {};
    const Box2dWorld::Profile& p = world_.last_profile();
    stages_ = {{{"collide", p.collide}, {"solve", p.solve}, {"solve_toi", p.solve_toi}}};
    return stages_;
  }

 private:
  Box2dWorld world_;
  mutable double contacts_ = 0.0;
  mutable std::array<StageTime, 3> stages_{};
  bool profiling_ = false;
};

}  // namespace

EngineDef register_box2d() {
  EngineDef e;
  e.name = "box2d";
  e.description = "Box2D 2.4.1 (Debian libbox2d), fixed rotation unless the scene rotates";
  e.keys = {whole_key("vel_iters", 8, 1, 1000, "velocity iterations"),
            whole_key("pos_iters", 3, 0, 1000, "position iterations"),
            whole_key("substeps", 1, 1, 1000, "world steps per scene step"),
            choice_key("skin", "compensate", {"compensate", "raw"},
                       "compensate: polygons built 7.5 mm smaller per side so boxes rest at their "
                       "faces"),
            whole_key("warm", 1, 0, 1, "warm starting"),
            whole_key("ccd", 1, 0, 2,
                      "continuous collision: 0 off, 1 against static and kinematic bodies "
                      "(Box2D's default), 2 every dynamic body a bullet"),
            whole_key("sleep", 0, 0, 1, "bodies at rest fall asleep, as games ship it")};
  e.capabilities = [](const EngineSpec&) {
    return Capabilities{true, true, true, true, true, true, true, true};
  };
  e.counters = counter_list();
  e.defaults = {"box2d"};
  e.reference = true;
  e.accurate = "box2d:vel_iters=20,pos_iters=10,substeps=8";
  e.sweep = {"vel_iters=1,2,4,8,16", "pos_iters=0,1,8", "substeps=2,4,8", "skin=raw"};
  e.benchmarks = {{"box2d", 150'000}, {"box2d:sleep=1", 150'000}};
  e.make = [](const EngineSpec& spec, const Scene& scene) -> std::unique_ptr<Engine> {
    return std::make_unique<Box2dEngine>(spec, scene);
  };
  // Box2D clamps each body's move in one world step to b2_maxTranslation (2 m in 2.4): at 60 Hz
  // and one sub-step nothing goes faster than 120 m/s, whatever its velocity says.
  e.limits = {{"moves no body more than this in one world step (b2_maxTranslation)",
               Box2dWorld::max_translation(), "m", [](const EngineSpec& spec, const Scene& scene) {
                 return Box2dWorld::max_translation() *
                        static_cast<double>(spec.get_int("substeps")) / scene.dt;
               }}};
  return e;
}

}  // namespace chainbench
