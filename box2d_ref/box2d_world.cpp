// SPDX-License-Identifier: MIT
#include "box2d_ref/box2d_world.h"

#include <box2d/box2d.h>

#include <algorithm>
#include <stdexcept>

namespace chainbench {
namespace {

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

}  // namespace

namespace {

// A conveyor's contacts: the tangent speed that makes friction drive the bodies' relative
// velocity along the contact's tangent to the belts' (Box2D solves dot(vB - vA, t) toward it,
// t the normal from A to B turned clockwise), dot(sA - sB, t).
class Belts final : public b2ContactListener {
 public:
  explicit Belts(const Scene& scene) : scene_(scene) {}
  void PreSolve(b2Contact* contact, const b2Manifold*) override {
    const Vec2d a = belt(contact->GetFixtureA()), b = belt(contact->GetFixtureB());
    if (a.x == b.x && a.y == b.y) return;
    b2WorldManifold m;
    contact->GetWorldManifold(&m);
    const double tx = m.normal.y, ty = -m.normal.x;
    contact->SetTangentSpeed(static_cast<float>((a.x - b.x) * tx + (a.y - b.y) * ty));
  }

 private:
  Vec2d belt(b2Fixture* f) const {
    return scene_.bodies[f->GetBody()->GetUserData().pointer].surface_velocity;
  }
  const Scene& scene_;
};

}  // namespace

Box2dWorld::~Box2dWorld() = default;

double Box2dWorld::max_translation() {
  return static_cast<double>(b2_maxTranslation);
}

double Box2dWorld::skin_shrink() {
  return b2_polygonRadius - 0.5 * b2_linearSlop;
}

Box2dWorld::Box2dWorld(const Scene& scene, const Box2dSettings& settings)
    : belts_(scene.has_belts() ? std::make_unique<Belts>(scene) : nullptr),
      world_(std::make_unique<b2World>(vec(scene.gravity))),
      scene_(scene),
      drives_(scene),
      dt_(scene.dt),
      settings_(settings) {
  if (settings.velocity_iterations < 1 || settings.position_iterations < 0 ||
      settings.substeps < 1 || settings.continuous < 0 || settings.continuous > 2) {
    throw std::invalid_argument("Box2dWorld: iterations, substeps or continuous out of range");
  }
  world_->SetAllowSleeping(settings.sleep);
  if (belts_) world_->SetContactListener(belts_.get());
  world_->SetContinuousPhysics(settings.continuous >= 1);
  world_->SetWarmStarting(settings.warm_starting);
  bodies_.assign(scene.bodies.size(), nullptr);
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    if (scene.bodies[i].alive(0)) add_body(i);
  }
}

void Box2dWorld::add_body(std::size_t i) {
  const Scene& scene = scene_;
  const Box2dSettings& settings = settings_;
  const SceneBody& sb = scene.bodies[i];
  b2BodyDef def;
  def.type = to_box2d(sb.kind);
  def.position = vec(sb.center);
  def.linearVelocity = sb.kind == BodyKind::kStatic ? b2Vec2(0.0f, 0.0f) : vec(sb.velocity);
  def.fixedRotation = !scene.rotation;
  def.allowSleep = settings.sleep;
  def.bullet = settings.continuous >= 2 && sb.kind == BodyKind::kDynamic;
  def.gravityScale = static_cast<float>(sb.gravity_scale);
  def.userData.pointer = i;  // the scene body, for the belts' listener
  b2Body* body = world_->CreateBody(&def);

  // Compensation never takes a box below half its declared size (boxes under 1.5 cm).
  const double shrink_x =
      settings.compensate_skin ? std::min(skin_shrink(), 0.5 * sb.half_extents.x) : 0.0;
  const double shrink_y =
      settings.compensate_skin ? std::min(skin_shrink(), 0.5 * sb.half_extents.y) : 0.0;
  b2PolygonShape box;
  box.SetAsBox(static_cast<float>(sb.half_extents.x - shrink_x),
               static_cast<float>(sb.half_extents.y - shrink_y));
  b2FixtureDef fixture;
  fixture.shape = &box;
  fixture.density = 0.0f;  // mass is set exactly below
  fixture.friction = static_cast<float>(scene.friction_of(sb));
  fixture.restitution = static_cast<float>(scene.restitution_of(sb));
  fixture.filter.categoryBits = sb.category_bits;
  fixture.filter.maskBits = sb.mask_bits;
  body->CreateFixture(&fixture);
  if (sb.kind == BodyKind::kDynamic) {
    b2MassData mass;
    mass.mass = static_cast<float>(sb.mass);
    mass.center = b2Vec2(0.0f, 0.0f);
    const double w = 2.0 * sb.half_extents.x, h = 2.0 * sb.half_extents.y;
    mass.I = static_cast<float>(sb.mass * (w * w + h * h) / 12.0);
    body->SetMassData(&mass);
  }
  bodies_[i] = body;
}

void Box2dWorld::remove_body(std::size_t i) {
  world_->DestroyBody(bodies_[i]);
  bodies_[i] = nullptr;
}

void Box2dWorld::step(int step_index) {
  // A driver sets the velocity at the start of the scene step only, as the scene format defines
  // it: sub-steps then refine the same physics instead of pushing harder (re-driving before every
  // sub-step would move a driven pusher's row up to 0.3 m further in push_row).
  drives_.advance(step_index);
  for (const Drive& d : drives_.active()) {
    b2Body* body = bodies_[d.body];
    b2Vec2 v = body->GetLinearVelocity();
    if (d.hold_x) v.x = static_cast<float>(d.velocity.x);
    if (d.hold_y) v.y = static_cast<float>(d.velocity.y);
    body->SetLinearVelocity(v);
    body->SetAwake(true);
  }
  const auto h = static_cast<float>(dt_ / settings_.substeps);
  profile_ = Profile{};
  for (int k = 0; k < settings_.substeps; ++k) {
    world_->Step(h, settings_.velocity_iterations, settings_.position_iterations);
    const b2Profile& p = world_->GetProfile();
    profile_.collide += p.collide;
    profile_.solve += p.solve;
    profile_.solve_toi += p.solveTOI;
  }
}

std::size_t Box2dWorld::touching_contacts() const {
  std::size_t n = 0;
  for (const b2Contact* c = world_->GetContactList(); c; c = c->GetNext())
    n += c->IsTouching();
  return n;
}

void Box2dWorld::read_state(std::span<Vec2d> positions, std::span<Vec2d> velocities,
                            std::span<double> angles) const {
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    const b2Body* b = bodies_[i];
    if (!b) continue;
    if (!positions.empty()) positions[i] = {b->GetPosition().x, b->GetPosition().y};
    if (!velocities.empty()) velocities[i] = {b->GetLinearVelocity().x, b->GetLinearVelocity().y};
    if (!angles.empty()) angles[i] = b->GetAngle();
  }
}

}  // namespace chainbench
