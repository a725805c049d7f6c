// SPDX-License-Identifier: MIT
// The collision-chaining solver of solver/ behind the Engine interface.
#include "engines/registry.h"
#include "model/drive_schedule.h"

#include <chain/world.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>

namespace chainbench {
namespace {

// The same bits, and not NaN: a NaN reads as changed every time, as it compares to the harness.
bool same(chain::Vec2 a, chain::Vec2 b) {
  return std::bit_cast<std::uint64_t>(a.x) == std::bit_cast<std::uint64_t>(b.x) &&
         std::bit_cast<std::uint64_t>(a.y) == std::bit_cast<std::uint64_t>(b.y) && a.x == a.x &&
         a.y == a.y;
}

chain::BodyType to_chain(BodyKind kind) {
  switch (kind) {
    case BodyKind::kStatic:
      return chain::BodyType::kStatic;
    case BodyKind::kKinematic:
      return chain::BodyType::kKinematic;
    case BodyKind::kDynamic:
      return chain::BodyType::kDynamic;
  }
  return chain::BodyType::kStatic;
}

chain::WorldDef world_def(const EngineSpec& spec, const Scene& scene) {
  chain::WorldDef def;
  def.variant =
      spec.get("variant") == "seed2014" ? chain::Variant::kSeed2014 : chain::Variant::kModern;
  def.velocity_rule =
      spec.get("velocity") == "zero" ? chain::VelocityRule::kZero : chain::VelocityRule::kInelastic;
  def.gravity = {scene.gravity.x, scene.gravity.y};
  def.max_passes = static_cast<int>(spec.get_int("passes"));
  def.budget_per_body = static_cast<int>(spec.get_int("budget"));
  def.seed_max_depth = static_cast<int>(spec.get_int("depth"));
  def.threads = static_cast<int>(spec.get_int("threads"));
  def.skip_rest = spec.get_int("skip_rest") != 0;
  return def;
}

enum Counter {
  kPasses,
  kContacts,
  kResolveCalls,
  kMaxDepth,
  kBudgetHits,
  kCrushEvents,
  kAtRest,
  kResting,
  kRedone,
  kCount
};
const std::vector<CounterDef>& counter_list() {
  static const std::vector<CounterDef> list = {
      {"passes", Aggregate::kMean, "contact passes per step", ""},
      {"contacts", Aggregate::kMean, "overlapping pairs found per step, all passes", ""},
      {"resolve_calls", Aggregate::kMean, "pair resolutions per step, chained ones included", ""},
      {"max_depth", Aggregate::kMax, "longest chain of nested resolutions", ""},
      {"budget_hits", Aggregate::kSum, "chains cut short by the work budget", "budget"},
      {"crush_events", Aggregate::kSum, "bodies squeezed between two immovable ones", "crushes"},
      {"skipped_steps", Aggregate::kSum, "steps skipped as the fixed point they were (skip_rest)",
       ""},
      {"resting_bodies", Aggregate::kMean,
       "bodies of resting islands left out per step, each the fixed point it was (skip_rest)", ""},
      {"redone_steps", Aggregate::kSum,
       "steps that left islands out, met one and were solved again whole (skip_rest)", ""}};
  return list;
}

class ChainEngine final : public Engine {
 public:
  ChainEngine(const EngineSpec& spec, const Scene& scene)
      : world_(world_def(spec, scene)), drives_(scene), dt_(scene.dt), scene_(scene) {
    ids_.assign(scene.bodies.size(), chain::BodyId{});
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
      if (scene.bodies[i].alive(0)) add_body(i);
    }
    flag_.assign(ids_.size(), 0);
  }

  void add_body(std::size_t i) override {
    const SceneBody& b = scene_.bodies[i];
    chain::BodyDef def;
    def.type = to_chain(b.kind);
    def.center = {b.center.x, b.center.y};
    def.half_extents = {b.half_extents.x, b.half_extents.y};
    def.velocity = {b.velocity.x, b.velocity.y};
    def.mass = b.mass;
    def.gravity_scale = b.gravity_scale;
    def.category_bits = b.category_bits;
    def.surface_velocity = {b.surface_velocity.x, b.surface_velocity.y};
    def.mask_bits = b.mask_bits;
    def.restitution = scene_.restitution_of(b);
    def.friction = scene_.friction_of(b);
    ids_[i] = world_.create_body(def);
    if (index_of_.size() <= ids_[i].value) index_of_.resize(ids_[i].value + 1, kNoIndex);
    index_of_[ids_[i].value] = static_cast<std::uint32_t>(i);
    reread_ = true;
  }

  void remove_body(std::size_t i) override {
    world_.destroy_body(ids_[i]);
    ids_[i] = chain::BodyId{};
    reread_ = true;
  }

  void step(int step_index) override {
    // A drive persists in the solver until cleared: only what changed at this step is told,
    // drives that begin or change and bodies whose drivers ended.
    drives_.advance(step_index);
    for (const std::size_t b : drives_.released()) {
      // A drive that ends as its body leaves went with the body.
      if (ids_[b] != chain::BodyId{}) world_.clear_drive(ids_[b]);
    }
    for (const Drive& d : drives_.changed()) {
      const chain::DriveAxes axes = d.hold_x && d.hold_y ? chain::DriveAxes::kBoth
                                    : d.hold_x           ? chain::DriveAxes::kX
                                                         : chain::DriveAxes::kY;
      world_.set_drive(ids_[d.body], {d.velocity.x, d.velocity.y}, axes);
    }
    world_.step(dt_);
  }

  void read_state(BodyState& out) const override {
    // In the world's storage order, which differs from the scene's: each body's state is read
    // once in a pass through memory and written to its scene index. Looking every scene index's
    // body up instead (read_state) costs a cache miss per body in a world beyond the cache.
    const std::size_t held = world_.body_count();
    stored_ids_.resize(held);
    positions_.resize(held);
    velocities_.resize(held);
    world_.read_all(stored_ids_, positions_, velocities_);
    reread_ = false;
    for (std::size_t k = 0; k < stored_ids_.size(); ++k) {
      const std::uint32_t i = index_of_[stored_ids_[k].value];
      out.position[i] = {positions_[k].x, positions_[k].y};
      out.velocity[i] = {velocities_[k].x, velocities_[k].y};
    }
  }

  // The world brings the copy of the last read, kept in storage order, up to date in one pass
  // and lists what it changed; a body the world stored elsewhere since (it renumbers its bodies
  // now and then) is compared with `state` instead. Only the bodies whose state differs are
  // written and listed.
  bool read_changes(BodyState& state, std::vector<std::uint32_t>& changed) const override {
    // The copy lists the bodies of the last read: after an add or a remove, read all again.
    if (reread_) return false;
    world_.update_all(stored_ids_, positions_, velocities_, slots_);
    changed.clear();
    for (const std::uint32_t k : slots_) {
      const chain::Vec2 p = positions_[k], v = velocities_[k];
      const std::uint32_t i = index_of_[stored_ids_[k].value];
      if (same(p, {state.position[i].x, state.position[i].y}) &&
          same(v, {state.velocity[i].x, state.velocity[i].y}))
        continue;  // moved here from another slot, unchanged
      state.position[i] = {p.x, p.y};
      state.velocity[i] = {v.x, v.y};
      changed.push_back(i);
    }
    // In scene order: sorted where few changed, from a pass over flags where many did.
    if (changed.size() <= stored_ids_.size() / 32) {
      std::sort(changed.begin(), changed.end());
      return true;
    }
    for (const std::uint32_t i : changed)
      flag_[i] = 1;
    changed.clear();
    for (std::uint32_t i = 0; i < flag_.size(); ++i) {
      if (flag_[i]) changed.push_back(i), flag_[i] = 0;
    }
    return true;
  }

  std::span<const CounterDef> counter_defs() const override { return counter_list(); }
  std::span<const double> counters() const override {
    const chain::StepStats& s = world_.last_step_stats();
    counters_ = {static_cast<double>(s.passes),        static_cast<double>(s.contacts),
                 static_cast<double>(s.resolve_calls), static_cast<double>(s.max_depth),
                 static_cast<double>(s.budget_hits),   static_cast<double>(s.crush_events),
                 static_cast<double>(s.skipped),       static_cast<double>(s.resting),
                 static_cast<double>(s.redone)};
    return counters_;
  }

  bool degraded() const override { return world_.last_step_stats().budget_hits > 0; }

  void measure_stages() override {
    world_.set_profiling(true);
    profiling_ = true;
  }
  std::span<const StageTime> stages() const override {
    if (!profiling_) return {};
    const chain::StepProfile& p = world_.last_step_profile();
    for (std::size_t i = 0; i < stages_.size(); ++i)
      stages_[i] = {chain::kStepStages[i].name, p.*chain::kStepStages[i].ms};
    return stages_;
  }

  std::span<const EngineEvent> events() const override {
    events_.clear();
    for (const chain::CrushEvent& c : world_.crush_events())
      events_.push_back({"crush", index_of_[c.body.value]});
    return events_;
  }

 private:
  chain::World world_;
  std::vector<chain::BodyId> ids_;
  DriveSchedule drives_;
  double dt_;
  mutable std::vector<chain::Vec2> positions_, velocities_;
  mutable std::array<double, kCount> counters_{};
  static constexpr std::uint32_t kNoIndex = 0xffffffffu;
  std::vector<std::uint32_t> index_of_;  // body id value -> scene index
  // The last read: read_all's ids, positions and velocities, in the world's order, and the slots
  // update_all changed.
  mutable std::vector<chain::BodyId> stored_ids_;
  mutable std::vector<std::uint32_t> slots_;
  mutable std::vector<std::uint8_t> flag_;  // per scene index, zero between reads
  mutable std::vector<EngineEvent> events_;
  mutable std::array<StageTime, std::size(chain::kStepStages)> stages_{};
  bool profiling_ = false;
  const Scene& scene_;          // outlives the engine
  mutable bool reread_ = true;  // bodies came or went since the last read_all
};

}  // namespace

EngineDef register_chain() {
  EngineDef e;
  e.name = "chain";
  e.description = "the collision-chaining solver of solver/ (no rotation)";
  KeyDef velocity = choice_key(
      "velocity", "inelastic", {"zero", "inelastic"},
      "velocity after a push: momentum shared (inelastic) or stopped into the push (zero)");
  velocity.depends_on = "variant";  // each variant's own rule
  velocity.default_when = {{"seed2014", "zero"}};
  e.keys = {choice_key("variant", "modern", {"modern", "seed2014"},
                       "modern: chaining done right; seed2014: the 2014 engine, quirks included"),
            velocity,
            whole_key("passes", 4, 1, 1000, "modern: contact passes per step, at most"),
            whole_key("budget", 64, 1, 1000000, "pair resolutions per body per step (+1024)"),
            whole_key("depth", 2048, 1, 16384, "seed2014: recursion depth limit"),
            whole_key("threads", 1, 1, chain::kMaxThreads,
                      "threads a step runs on, the caller's included (same bits for any count)"),
            whole_key("skip_rest", 1, 0, 1,
                      "modern: skip a step, or the resting islands of one, that would rebuild "
                      "the bits it starts from (same bits either way)")};
  e.capabilities = [](const EngineSpec& spec) {
    Capabilities c;
    c.kinematic = true;
    c.axis_drives = true;
    c.lifetimes = true;
    c.filtering = true;
    c.belts = spec.get("variant") == "modern";     // friction's, which the 2014 engine had not
    c.friction = spec.get("variant") == "modern";  // the 2014 engine had none
    c.restitution = spec.get("velocity") == "inelastic";  // the zero rule stops, never bounces
    return c;
  };
  e.counters = counter_list();
  e.stats_block = "chain_stats";
  e.defaults = {"chain", "chain:variant=seed2014"};
  e.sweep = {"velocity=zero", "variant=seed2014", "variant=seed2014;velocity=inelastic",
             "passes=1,2", "budget=4,16"};
  // skip_rest=0 beside the default: what solving a world at rest costs, which the default skips.
  e.benchmarks = {
      {"chain", 2'000'000}, {"chain:skip_rest=0", 150'000}, {"chain:variant=seed2014", 150'000}};
  // The modern solver is the one under test: stress fails where it is not right.
  e.gate = "chain";
  const char* through =
      "created twice as dense as it can hold, the pile's first steps move boxes metres by series "
      "of pushes; each push stops short of other boxes' centres (its own chain's walls excepted, "
      "so squeezes are found), but the step's net motion, judged as one straight move, can cross "
      "a third box";
  e.known_failures = {{"overlapping_pile n=1000", "tunnelled", through},
                      {"overlapping_pile n=200", "tunnelled", through}};
  e.make = [](const EngineSpec& spec, const Scene& scene) -> std::unique_ptr<Engine> {
    return std::make_unique<ChainEngine>(spec, scene);
  };
  return e;
}

}  // namespace chainbench
