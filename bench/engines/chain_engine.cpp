// The chaining solver behind the Engine interface.
#include "engine.h"

#include <chain/world.h>

#include <algorithm>

namespace chainbench {
namespace {

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
  return def;
}

class ChainEngine final : public Engine {
 public:
  ChainEngine(const EngineSpec& spec, const Scene& scene)
      : world_(world_def(spec, scene)),
        drivers_(scene.drivers),
        dt_(scene.dt),
        now_(scene.bodies.size(), 0),
        was_(scene.bodies.size(), 0) {
    for (const Driver& d : drivers_)
      driven_bodies_.push_back(d.body);
    std::sort(driven_bodies_.begin(), driven_bodies_.end());
    driven_bodies_.erase(std::unique(driven_bodies_.begin(), driven_bodies_.end()),
                         driven_bodies_.end());
    ids_.reserve(scene.bodies.size());
    for (const SceneBody& b : scene.bodies) {
      chain::BodyDef def;
      def.type = to_chain(b.kind);
      def.center = {b.center.x, b.center.y};
      def.half_extents = {b.half_extents.x, b.half_extents.y};
      def.velocity = {b.velocity.x, b.velocity.y};
      def.mass = b.mass;
      def.gravity_scale = b.gravity_scale;
      def.restitution = scene.restitution_of(b);
      ids_.push_back(world_.create_body(def));
    }
    positions_.resize(ids_.size());
    velocities_.resize(ids_.size());
  }

  void step(int step_index) override {
    // Drivers hold the body's velocity for their window (the last active one wins); outside
    // every window the body is free and keeps the velocity it has.
    for (const std::size_t b : driven_bodies_)
      now_[b] = 0;
    for (const Driver& d : drivers_) {
      if (step_index >= d.from_step && step_index < d.to_step) {
        world_.set_drive(ids_[d.body], {d.velocity.x, d.velocity.y});
        now_[d.body] = 1;
      }
    }
    for (const std::size_t b : driven_bodies_) {
      if (was_[b] && !now_[b]) world_.clear_drive(ids_[b]);
      was_[b] = now_[b];
    }
    world_.step(dt_);
  }

  void read_state(BodyState& out) const override {
    world_.read_state(ids_, positions_, velocities_);
    for (std::size_t i = 0; i < ids_.size(); ++i) {
      out.position[i] = {positions_[i].x, positions_[i].y};
      out.velocity[i] = {velocities_[i].x, velocities_[i].y};
    }
  }

  const chain::StepStats* chain_stats() const override { return &world_.last_step_stats(); }

 private:
  chain::World world_;
  std::vector<chain::BodyId> ids_;
  std::vector<Driver> drivers_;
  double dt_;
  std::vector<std::size_t> driven_bodies_;
  std::vector<std::uint8_t> now_, was_;  // per body: driven this step, driven last step
  mutable std::vector<chain::Vec2> positions_, velocities_;
};

}  // namespace

std::unique_ptr<Engine> make_chain_engine(const EngineSpec& spec, const Scene& scene) {
  return std::make_unique<ChainEngine>(spec, scene);
}

}  // namespace chainbench
