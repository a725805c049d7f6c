// SPDX-License-Identifier: MIT
// Box2D v3 (an installed release, found by CMake: box2d3/CMakeLists.txt) behind the Engine
// interface.
//
// Every body is one box polygon at its declared size (v3 polygons have no skin), rotation fixed
// unless the scene rotates, mass set exactly from the scene, friction and restitution combined by
// the scene format's rule through the world's mixing callbacks. One scene step is one
// b2World_Step with `substeps` sub-steps. Its soft contacts sag under load (docs/box2d3.md), so no
// constant offset could rest boxes at their faces: none is applied. With threads > 1 Box2D's work
// runs on this adapter's own thread pool (box2d3_tasks.h); Box2D's answer does not depend on it.
#include "engines/box2d3_tasks.h"
#include "engines/registry.h"
#include "model/drive_schedule.h"

#include <box2d/box2d.h>

#include <array>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

namespace chainbench {
namespace {

const std::vector<CounterDef>& counter_list() {
  static const std::vector<CounterDef> list = {
      {"contacts", Aggregate::kMean,
       "contacts whose manifold has a point after each step, sleeping ones included", ""}};
  return list;
}

// The scene format's rules (docs/scene-format.md): sqrt(a b) and the larger of the two.
float mix_friction(float a, int, float b, int) {
  return std::sqrt(a * b);
}
float mix_restitution(float a, int, float b, int) {
  return a > b ? a : b;
}

b2BodyType to_box2d(BodyKind kind) {
  switch (kind) {
    case BodyKind::kStatic:
      return b2_staticBody;
    case BodyKind::kKinematic:
      return b2_kinematicBody;
    case BodyKind::kDynamic:
      return b2_dynamicBody;
  }
  return b2_staticBody;
}

b2Vec2 vec(Vec2d v) {
  return {static_cast<float>(v.x), static_cast<float>(v.y)};
}

std::string version() {
  const b2Version v = b2GetVersion();
  return std::to_string(v.major) + "." + std::to_string(v.minor) + "." + std::to_string(v.revision);
}

class Box2d3Engine final : public Engine {
 public:
  Box2d3Engine(const EngineSpec& spec, const Scene& scene)
      : scene_(scene),
        drives_(scene),
        dt_(static_cast<float>(scene.dt)),
        substeps_(static_cast<int>(spec.get_int("substeps"))) {
    const int threads = static_cast<int>(spec.get_int("threads"));
    const int ccd = static_cast<int>(spec.get_int("ccd"));
    const bool sleep = spec.get_int("sleep") != 0;
    b2WorldDef def = b2DefaultWorldDef();
    def.gravity = vec(scene.gravity);
    def.contactHertz = static_cast<float>(spec.get_number("hertz"));
    def.contactDampingRatio = static_cast<float>(spec.get_number("damping"));
    def.maxContactPushSpeed = static_cast<float>(spec.get_number("push"));
    def.maximumLinearSpeed = static_cast<float>(spec.get_number("max_speed"));
    def.frictionCallback = mix_friction;
    def.restitutionCallback = mix_restitution;
    def.enableSleep = sleep;
    def.enableContinuous = ccd >= 1;
    if (threads > 1) {
      pool_ = std::make_unique<TaskPool>(threads);
      def.workerCount = threads;
      def.enqueueTask = TaskPool::enqueue_callback;
      def.finishTask = TaskPool::finish_callback;
      def.userTaskContext = pool_.get();
    }
    world_ = b2CreateWorld(&def);
    b2World_EnableWarmStarting(world_, spec.get_int("warm") != 0);
    b2World_EnableSpeculative(world_, spec.get_int("speculative") != 0);

    sleep_ = sleep;
    bullets_ = ccd >= 2;
    bodies_.assign(scene.bodies.size(), b2_nullBodyId);
    shapes_.assign(scene.bodies.size(), b2_nullShapeId);
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
      if (scene.bodies[i].alive(0)) add_body(i);
    }
  }

  void add_body(std::size_t i) override {
    const SceneBody& sb = scene_.bodies[i];
    b2BodyDef body = b2DefaultBodyDef();
    body.type = to_box2d(sb.kind);
    body.position = vec(sb.center);
    if (sb.kind != BodyKind::kStatic) body.linearVelocity = vec(sb.velocity);
    body.gravityScale = static_cast<float>(sb.gravity_scale);
    body.fixedRotation = !scene_.rotation;
    body.enableSleep = sleep_;
    body.isBullet = bullets_ && sb.kind == BodyKind::kDynamic;
    const b2BodyId id = b2CreateBody(world_, &body);

    b2ShapeDef shape = b2DefaultShapeDef();
    shape.material.friction = static_cast<float>(scene_.friction_of(sb));
    shape.material.restitution = static_cast<float>(scene_.restitution_of(sb));
    shape.filter.categoryBits = sb.category_bits;
    // v3's tangent speed runs along each contact's tangent (the normal turned clockwise): on the
    // top face that is +x, the belt's direction (scene belts run along x only).
    shape.material.tangentSpeed = static_cast<float>(sb.surface_velocity.x);
    shape.filter.maskBits = sb.mask_bits;
    // The shape updates the body's mass (then set exactly below) so that v3 also learns the
    // body's extent: without it a body's minExtent stays huge, no body is ever fast and
    // continuous collision never runs, whatever `ccd` says (docs/box2d3.md §2).
    const b2Polygon box =
        b2MakeBox(static_cast<float>(sb.half_extents.x), static_cast<float>(sb.half_extents.y));
    shapes_[i] = b2CreatePolygonShape(id, &shape, &box);
    if (sb.kind == BodyKind::kDynamic) {
      // Without rotation the inertia stays 0, which is what keeps v3 from turning the body.
      const double w = 2.0 * sb.half_extents.x, h = 2.0 * sb.half_extents.y;
      const double inertia = scene_.rotation ? sb.mass * (w * w + h * h) / 12.0 : 0.0;
      b2Body_SetMassData(
          id, b2MassData{static_cast<float>(sb.mass), {0.0f, 0.0f}, static_cast<float>(inertia)});
    }
    bodies_[i] = id;
  }

  void remove_body(std::size_t i) override {
    b2DestroyBody(bodies_[i]);  // and its shape
    bodies_[i] = b2_nullBodyId;
    shapes_[i] = b2_nullShapeId;
  }

  ~Box2d3Engine() override { b2DestroyWorld(world_); }  // before the pool it may still call
  Box2d3Engine(const Box2d3Engine&) = delete;
  Box2d3Engine& operator=(const Box2d3Engine&) = delete;

  // Drives set the velocity at the start of the scene step only, as the scene format defines it
  // and the other adapters do; v3's own sub-steps then refine that one step.
  void step(int step_index) override {
    drives_.advance(step_index);
    for (const Drive& d : drives_.active()) {
      const b2BodyId id = bodies_[d.body];
      b2Vec2 v = b2Body_GetLinearVelocity(id);
      if (d.hold_x) v.x = static_cast<float>(d.velocity.x);
      if (d.hold_y) v.y = static_cast<float>(d.velocity.y);
      b2Body_SetLinearVelocity(id, v);
      b2Body_SetAwake(id, true);
    }
    b2World_Step(world_, dt_, substeps_);
  }

  void read_state(BodyState& out) const override {
    for (std::size_t i = 0; i < bodies_.size(); ++i) {
      if (B2_IS_NULL(bodies_[i])) continue;
      const b2Vec2 p = b2Body_GetPosition(bodies_[i]), v = b2Body_GetLinearVelocity(bodies_[i]);
      out.position[i] = {p.x, p.y};
      out.velocity[i] = {v.x, v.y};
      out.angle[i] = b2Rot_GetAngle(b2Body_GetRotation(bodies_[i]));
    }
  }

  std::span<const CounterDef> counter_defs() const override { return counter_list(); }
  // Counted here, outside the timed step: each contact is listed by both its bodies, and counted
  // by the one whose shape is its shape A.
  std::span<const double> counters() const override {
    std::size_t n = 0;
    for (std::size_t i = 0; i < bodies_.size(); ++i) {
      if (B2_IS_NULL(bodies_[i])) continue;
      const int capacity = b2Body_GetContactCapacity(bodies_[i]);
      if (capacity == 0) continue;
      if (contact_buffer_.size() < static_cast<std::size_t>(capacity))
        contact_buffer_.resize(static_cast<std::size_t>(capacity));
      const int count = b2Body_GetContactData(bodies_[i], contact_buffer_.data(), capacity);
      for (int c = 0; c < count; ++c) {
        const b2ContactData& data = contact_buffer_[static_cast<std::size_t>(c)];
        if (data.manifold.pointCount > 0 && B2_ID_EQUALS(data.shapeIdA, shapes_[i])) ++n;
      }
    }
    contacts_ = static_cast<double>(n);
    return {&contacts_, 1};
  }
  // v3 times its stages whether asked or not (b2World_GetProfile): its top-level ones.
  void measure_stages() override { profiling_ = true; }
  std::span<const StageTime> stages() const override {
    if (!profiling_) return {};
    const b2Profile p = b2World_GetProfile(world_);
    stages_ = {
        {{"pairs", p.pairs}, {"collide", p.collide}, {"solve", p.solve}, {"sensors", p.sensors}}};
    return stages_;
  }

 private:
  std::unique_ptr<TaskPool> pool_;  // outlives the world, which calls it
  b2WorldId world_{};
  const Scene& scene_;  // outlives the engine
  bool sleep_ = false, bullets_ = false;
  std::vector<b2BodyId> bodies_;   // per scene body, null while it is not in the world
  std::vector<b2ShapeId> shapes_;  // one per body, in scene order
  DriveSchedule drives_;
  float dt_;
  int substeps_;
  mutable std::vector<b2ContactData> contact_buffer_;
  mutable double contacts_ = 0.0;
  mutable std::array<StageTime, 4> stages_{};
  bool profiling_ = false;
};

}  // namespace

EngineDef register_box2d3() {
  EngineDef e;
  e.name = "box2d3";
  e.description = "Box2D " + version() +
                  " (installed, found by CMake), fixed rotation unless the scene rotates";
  e.keys = {
      whole_key("substeps", 4, 1, 1000, "Box2D v3's sub-steps per scene step"),
      whole_key("sleep", 0, 0, 1, "bodies at rest fall asleep, as games ship it"),
      whole_key("threads", 1, 1, 64,
                "workers (v3's workerCount) on the adapter's own threads; same answer for any"),
      whole_key("ccd", 1, 0, 2,
                "continuous collision: 0 off, 1 against static bodies (v3's default), 2 every "
                "dynamic body a bullet (also against kinematic ones; v3 bullets skip bullets)"),
      number_key("hertz", 30.0, 0.01, 1e6,
                 "contact stiffness, Hz (v3 silently uses at most 1/8 of the sub-step rate)"),
      number_key("damping", 10.0, 0.0, 1e6, "contact damping ratio"),
      number_key("push", 3.0, 0.0, 1e6, "fastest overlap recovery, m/s (maxContactPushSpeed)"),
      whole_key("speculative", 1, 0, 1,
                "speculative contact points (v3's testing switch b2World_EnableSpeculative)"),
      whole_key("warm", 1, 0, 1, "warm starting"),
      number_key("max_speed", 400.0, 0.01, 1e6, "speed limit of every body, m/s")};
  e.capabilities = [](const EngineSpec&) {
    return Capabilities{true, true, true, true, true, true, true, true};
  };
  e.counters = counter_list();
  e.defaults = {"box2d3"};
  e.accurate = "box2d3:substeps=16";
  e.sweep = {"substeps=1,2,8", "hertz=10,20", "threads=2"};
  e.benchmarks = {{"box2d3", 150'000}, {"box2d3:sleep=1", 150'000}};
  e.make = [](const EngineSpec& spec, const Scene& scene) -> std::unique_ptr<Engine> {
    return std::make_unique<Box2d3Engine>(spec, scene);
  };
  // v3 clamps every body's speed in each sub-step (docs/box2d3.md §5.2).
  e.limits = {{"moves no body faster than this (maximumLinearSpeed, the key max_speed)", 400.0,
               "m/s",
               [](const EngineSpec& spec, const Scene&) { return spec.get_number("max_speed"); }}};
  return e;
}

}  // namespace chainbench
