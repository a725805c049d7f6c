// SPDX-License-Identifier: MIT
// Chipmunk2D 7 (Debian libchipmunk) behind the Engine interface: a second reference engine.
//
// Boxes are box shapes without rounding; rotation is fixed by an infinite moment unless the scene
// rotates. Chipmunk lets contacts sink up to its collision slop before it pushes them apart (0.1,
// meant for pixels), so at rest its shapes overlap by the slop: the default slop is 5 mm, and each
// shape is built slop / 2 larger per side than its box, so that boxes rest at their declared faces,
// as the Box2D adapter's skin compensation does. Friction and restitution of a contact combine as
// the scene format says (the square root of the product, and the larger of the two), not Chipmunk's
// product.
#include "engines/registry.h"
#include "model/drive_schedule.h"

#include <chipmunk/chipmunk.h>

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

namespace chainbench {
namespace {

const std::vector<CounterDef>& counter_list() {
  static const std::vector<CounterDef> list = {
      {"contacts", Aggregate::kMean, "touching pairs after each step, sleeping ones included", ""}};
  return list;
}

// Freeing a space wakes its sleeping bodies, which reads their shapes: the space goes first, and
// its shapes and bodies after it.
struct SpaceDeleter {
  void operator()(cpSpace* space) const {
    std::vector<cpShape*> shapes;
    std::vector<cpBody*> bodies;
    cpSpaceEachShape(
        space,
        [](cpShape* s, void* out) { static_cast<std::vector<cpShape*>*>(out)->push_back(s); },
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
};

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

class ChipmunkEngine final : public Engine {
 public:
  ChipmunkEngine(const EngineSpec& spec, const Scene& scene)
      : space_((quiet_first_space(), cpSpaceNew())),
        drives_(scene),
        dt_(scene.dt / static_cast<double>(spec.get_int("substeps"))),
        substeps_(static_cast<int>(spec.get_int("substeps"))),
        gravity_scale_(scene.bodies.size(), 1.0),
        scene_(scene) {
    cpSpace* space = space_.get();
    cpSpaceSetGravity(space, cpv(scene.gravity.x, scene.gravity.y));
    cpSpaceSetIterations(space, static_cast<int>(spec.get_int("iterations")));
    const double slop = spec.get_number("slop");
    cpSpaceSetCollisionSlop(space, slop);
    cpSpaceSetCollisionBias(space, spec.get_number("bias"));
    if (spec.get_int("sleep") != 0) cpSpaceSetSleepTimeThreshold(space, 0.5);
    cpSpaceAddDefaultCollisionHandler(space)->preSolveFunc = combine;
    grow_ = spec.get("skin") == "compensate" ? 0.5 * slop : 0.0;
    bodies_.assign(scene.bodies.size(), nullptr);
    shapes_.assign(scene.bodies.size(), nullptr);
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
      if (scene.bodies[i].alive(0)) add_body(i);
    }
  }

  void add_body(std::size_t i) override {
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
    if (b.kind == BodyKind::kStatic) cpSpaceReindexShapesForBody(space, body);
    bodies_[i] = body;
    shapes_[i] = shape;
  }

  void remove_body(std::size_t i) override {
    cpSpace* space = space_.get();
    cpSpaceRemoveShape(space, shapes_[i]);
    cpSpaceRemoveBody(space, bodies_[i]);
    cpShapeFree(shapes_[i]);
    cpBodyFree(bodies_[i]);
    bodies_[i] = nullptr;
    shapes_[i] = nullptr;
  }

  void step(int step_index) override {
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

  void read_state(BodyState& out) const override {
    for (std::size_t i = 0; i < bodies_.size(); ++i) {
      if (!bodies_[i]) continue;
      const cpVect p = cpBodyGetPosition(bodies_[i]), v = cpBodyGetVelocity(bodies_[i]);
      out.position[i] = {p.x, p.y};
      out.velocity[i] = {v.x, v.y};
      out.angle[i] = cpBodyGetAngle(bodies_[i]);
    }
  }

  std::span<const CounterDef> counter_defs() const override { return counter_list(); }
  // Counted here, outside the timed step. The space's own list of arbiters holds the pairs awake
  // in the last step only; a sleeping body keeps its pairs in its own list, so every dynamic
  // body's list is walked and each pair counted once: from its lower body when both are dynamic.
  std::span<const double> counters() const override {
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
    contacts_ = static_cast<double>(n);
    return {&contacts_, 1};
  }

 private:
  std::unique_ptr<cpSpace, SpaceDeleter> space_;
  std::vector<cpBody*> bodies_;  // per scene body, null while it is not in the space
  DriveSchedule drives_;
  double dt_;
  int substeps_;
  std::vector<double> gravity_scale_;  // per body; dynamic bodies point their user data here
  const Scene& scene_;
  double grow_ = 0.0;             // what skin compensation adds to each half extent
  std::vector<cpShape*> shapes_;  // per scene body, null while it is not in the space
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
      number_key("bias", std::pow(1.0 - 0.1, 60.0), 0.0, 1.0,
                 "share of an overlap left after one second of correction"),
      choice_key("skin", "compensate", {"compensate", "raw"},
                 "compensate: shapes built slop/2 larger per side so boxes rest at their faces"),
      whole_key("sleep", 0, 0, 1, "bodies at rest fall asleep, as games ship it")};
  e.capabilities = [](const EngineSpec&) {
    return Capabilities{true, true, true, true, true, true};
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
