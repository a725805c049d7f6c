// SPDX-License-Identifier: MIT
#include "chipmunk_ref/chipmunk_world.h"

#include <chipmunk/chipmunk.h>

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace chainbench {
namespace {

// Chipmunk has no per-body gravity scale: each dynamic body's velocity update scales gravity by
// its own, kept in its user data.
void scaled_gravity(cpBody* body, cpVect gravity, cpFloat damping, cpFloat dt) {
  const double scale = *static_cast<const double*>(cpBodyGetUserData(body));
  cpBodyUpdateVelocity(body, cpvmult(gravity, scale), damping, dt);
}

cpBool combine(cpArbiter* arb, cpSpace*, cpDataPointer) {
  CP_ARBITER_GET_SHAPES(arb, a, b);
  cpArbiterSetFriction(arb, std::sqrt(cpShapeGetFriction(a) * cpShapeGetFriction(b)));
  cpArbiterSetRestitution(arb, std::max(cpShapeGetElasticity(a), cpShapeGetElasticity(b)));
  return cpTrue;
}

// Debian's libchipmunk is built with its debug checks on, and its first space prints a banner to
// stdout, into chainbench's tables: the first space is made once with stdout pointed elsewhere.
void quiet_first_space() {
  static const bool done = [] {
    std::fflush(stdout);
    const int saved = dup(STDOUT_FILENO);
    const int null = open("/dev/null", O_WRONLY);
    if (saved >= 0 && null >= 0) dup2(null, STDOUT_FILENO);
    cpSpaceFree(cpSpaceNew());
    std::fflush(stdout);
    if (saved >= 0) dup2(saved, STDOUT_FILENO), close(saved);
    if (null >= 0) close(null);
    return true;
  }();
  (void)done;
}

}  // namespace

// Freeing a space wakes its sleeping bodies, which reads their shapes: the space goes first, and
// its shapes and bodies after it.
void ChipmunkWorld::SpaceDeleter::operator()(cpSpace* space) const {
  std::vector<cpShape*> shapes;
  std::vector<cpBody*> bodies;
  cpSpaceEachShape(
      space, [](cpShape* s, void* out) { static_cast<std::vector<cpShape*>*>(out)->push_back(s); },
      &shapes);
  cpSpaceEachBody(
      space, [](cpBody* b, void* out) { static_cast<std::vector<cpBody*>*>(out)->push_back(b); },
      &bodies);
  cpSpaceFree(space);
  for (cpShape* s : shapes)
    cpShapeFree(s);
  for (cpBody* b : bodies)
    cpBodyFree(b);
}

ChipmunkWorld::ChipmunkWorld(const Scene& scene, const ChipmunkSettings& settings)
    : space_((quiet_first_space(), cpSpaceNew())),
      scene_(scene),
      bodies_(scene.bodies.size(), nullptr),
      shapes_(scene.bodies.size(), nullptr),
      gravity_scale_(scene.bodies.size(), 1.0),
      drives_(scene),
      dt_(scene.dt / static_cast<double>(settings.substeps)),
      substeps_(settings.substeps),
      grow_(settings.compensate_skin ? 0.5 * settings.slop : 0.0) {
  cpSpace* space = space_.get();
  cpSpaceSetGravity(space, cpv(scene.gravity.x, scene.gravity.y));
  cpSpaceSetIterations(space, settings.iterations);
  cpSpaceSetCollisionSlop(space, settings.slop);
  cpSpaceSetCollisionBias(space, settings.bias);
  if (settings.sleep) cpSpaceSetSleepTimeThreshold(space, 0.5);
  cpSpaceAddDefaultCollisionHandler(space)->preSolveFunc = combine;
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    if (scene.bodies[i].alive(0)) add_body(i);
  }
}

ChipmunkWorld::~ChipmunkWorld() = default;

void ChipmunkWorld::add_body(std::size_t i) {
  cpSpace* space = space_.get();
  const SceneBody& b = scene_.bodies[i];
  const double w = 2.0 * b.half_extents.x, h = 2.0 * b.half_extents.y;
  cpBody* body = nullptr;
  switch (b.kind) {
    case BodyKind::kStatic:
      body = cpBodyNewStatic();
      break;
    case BodyKind::kKinematic:
      body = cpBodyNewKinematic();
      break;
    case BodyKind::kDynamic:
      body = cpBodyNew(b.mass, scene_.rotation ? cpMomentForBox(b.mass, w, h) : INFINITY);
      gravity_scale_[i] = b.gravity_scale;
      cpBodySetUserData(body, &gravity_scale_[i]);
      cpBodySetVelocityUpdateFunc(body, scaled_gravity);
      break;
  }
  cpSpaceAddBody(space, body);
  cpBodySetPosition(body, cpv(b.center.x, b.center.y));
  if (b.kind != BodyKind::kStatic) cpBodySetVelocity(body, cpv(b.velocity.x, b.velocity.y));
  const double gx = b.half_extents.x + grow_, gy = b.half_extents.y + grow_;
  cpShape* shape = cpSpaceAddShape(space, cpBoxShapeNew2(body, cpBBNew(-gx, -gy, gx, gy), 0.0));
  cpShapeSetFriction(shape, scene_.friction_of(b));
  cpShapeSetElasticity(shape, scene_.restitution_of(b));
  // Chipmunk's filter rule is Box2D's: each one's categories in the other's mask.
  cpShapeSetFilter(shape, cpShapeFilterNew(CP_NO_GROUP, b.category_bits, b.mask_bits));
  // Chipmunk's surface velocity is the belt's: friction drives what touches it to move with it.
  cpShapeSetSurfaceVelocity(shape, cpv(b.surface_velocity.x, b.surface_velocity.y));
  if (b.kind == BodyKind::kStatic) cpSpaceReindexShapesForBody(space, body);
  bodies_[i] = body;
  shapes_[i] = shape;
}

void ChipmunkWorld::remove_body(std::size_t i) {
  cpSpace* space = space_.get();
  cpSpaceRemoveShape(space, shapes_[i]);
  cpSpaceRemoveBody(space, bodies_[i]);
  cpShapeFree(shapes_[i]);
  cpBodyFree(bodies_[i]);
  bodies_[i] = nullptr;
  shapes_[i] = nullptr;
}

void ChipmunkWorld::step(int step_index) {
  drives_.advance(step_index);
  for (const Drive& d : drives_.active()) {
    cpBody* body = bodies_[d.body];
    cpVect v = cpBodyGetVelocity(body);
    if (d.hold_x) v.x = d.velocity.x;
    if (d.hold_y) v.y = d.velocity.y;
    cpBodySetVelocity(body, v);
    cpBodyActivate(body);
  }
  for (int k = 0; k < substeps_; ++k)
    cpSpaceStep(space_.get(), dt_);
}

void ChipmunkWorld::read_state(std::span<Vec2d> positions, std::span<Vec2d> velocities,
                               std::span<double> angles) const {
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    if (!bodies_[i]) continue;
    const cpVect p = cpBodyGetPosition(bodies_[i]), v = cpBodyGetVelocity(bodies_[i]);
    if (!positions.empty()) positions[i] = {p.x, p.y};
    if (!velocities.empty()) velocities[i] = {v.x, v.y};
    if (!angles.empty()) angles[i] = cpBodyGetAngle(bodies_[i]);
  }
}

// The space's own list of arbiters holds the pairs awake in the last step only; a sleeping body
// keeps its pairs in its own list, so every dynamic body's list is walked and each pair counted
// once: from its lower body when both are dynamic.
std::size_t ChipmunkWorld::touching_pairs() const {
  std::size_t n = 0;
  for (cpBody* body : bodies_) {
    if (!body || cpBodyGetType(body) != CP_BODY_TYPE_DYNAMIC) continue;
    cpBodyEachArbiter(
        body,
        [](cpBody* self, cpArbiter* arb, void* count) {
          CP_ARBITER_GET_BODIES(arb, a, b);
          cpBody* other = a == self ? b : a;
          const bool once = cpBodyGetType(other) != CP_BODY_TYPE_DYNAMIC || self < other;
          if (once && cpArbiterGetCount(arb) > 0) ++*static_cast<std::size_t*>(count);
        },
        &n);
  }
  return n;
}

}  // namespace chainbench
