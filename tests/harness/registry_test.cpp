// SPDX-License-Identifier: MIT
// The engine registry: every adapter's declaration is consistent (keys, defaults, grids, gates
// and benchmarks all parse), and every capability an engine claims is physically there, while a
// scene that needs one it lacks is refused by name instead of run wrong.
#include "engines/registry.h"
#include "support/input_error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

namespace chainbench {
namespace {

// The engines that can be built without a file (a plugin needs its library: plugin_test.cpp).
std::vector<const EngineDef*> self_contained_engines() {
  std::vector<const EngineDef*> out;
  for (const EngineDef& e : engine_registry()) {
    const bool needs_file =
        std::any_of(e.keys.begin(), e.keys.end(), [](const KeyDef& k) { return k.file; });
    if (!needs_file) out.push_back(&e);
  }
  return out;
}

TEST(Registry, EveryEngineDeclaresAConsistentSpec) {
  std::set<std::string> names;
  for (const EngineDef& e : engine_registry()) {
    SCOPED_TRACE(e.name);
    EXPECT_TRUE(names.insert(e.name).second) << "two engines named " << e.name;
    EXPECT_FALSE(e.description.empty());
    EXPECT_TRUE(e.make && e.capabilities);
    std::set<std::string> keys;
    for (const KeyDef& k : e.keys) {
      EXPECT_TRUE(keys.insert(k.name).second) << "key " << k.name << " declared twice";
      EXPECT_FALSE(k.help.empty()) << k.name;
      if (!k.depends_on.empty()) {
        EXPECT_TRUE(keys.count(k.depends_on)) << k.name << " depends on a later or unknown key";
      }
    }
    for (const std::string& spec : e.defaults)
      EXPECT_NO_THROW(parse_engine_spec(spec)) << spec;
    if (!e.accurate.empty()) {
      EXPECT_NO_THROW(parse_engine_spec(e.accurate));
    }
    if (!e.gate.empty()) {
      EXPECT_NO_THROW(parse_engine_spec(e.gate));
    }
    for (const std::string& knob : e.sweep)
      EXPECT_NO_THROW(parse_grid(e.name + ":" + knob)) << knob;
    for (const auto& [spec, bodies] : e.benchmarks) {
      EXPECT_NO_THROW(parse_engine_spec(spec)) << spec;
      EXPECT_GT(bodies, 0u);
    }
  }
}

// A self-contained engine's spec at its defaults prints back to itself, and its label is its name.
TEST(Registry, DefaultSpecsRoundTrip) {
  for (const EngineDef* e : self_contained_engines()) {
    SCOPED_TRACE(e->name);
    const EngineSpec spec = parse_engine_spec(e->name);
    EXPECT_EQ(spec.label(), e->name);
    EXPECT_EQ(parse_engine_spec(spec.str()), spec);
    EXPECT_EQ(spec.settings.size(), e->keys.size());
  }
}

TEST(Registry, ExactlyOneDefaultReferenceAndItRunsByDefault) {
  int references = 0;
  for (const EngineDef& e : engine_registry())
    references += e.reference ? 1 : 0;
  EXPECT_EQ(references, 1);
  const EngineSpec reference = default_reference();
  const std::vector<EngineSpec> defaults = default_engines();
  EXPECT_NE(std::find(defaults.begin(), defaults.end(), reference), defaults.end());
}

// Plain scenes for the capability checks: metres, kilograms, seconds, gravity (0, -10).
Scene ground_and(const SceneBody& body, int steps) {
  Scene s;
  s.name = "capability";
  s.steps = steps;
  s.bodies.push_back({"ground", BodyKind::kStatic, {0, -0.5}, {50, 0.5}, {}, 0.0, 1.0, {}, {}});
  s.bodies.push_back(body);
  return s;
}

std::vector<BodyState> trajectory(const EngineSpec& spec, const Scene& s) {
  auto engine = make_engine(spec, s);
  std::vector<BodyState> out;
  for (int k = 0; k < s.steps; ++k) {
    engine->step(k);
    out.emplace_back(s.bodies.size());
    engine->read_state(out.back());
  }
  return out;
}

// Friction: a box sliding at 4 m/s on a floor with friction 0.5 stops after v^2 / (2 mu g) = 1.6 m.
// The tolerance, 5 cm, covers one step's travel at the start (6.7 cm at 4 m/s is the upper bound
// of where a step-discrete stop can land; the engines land within 3 cm).
TEST(Capabilities, FrictionIsThereWhereClaimedAndRefusedWhereNot) {
  SceneBody box{"box", BodyKind::kDynamic, {0, 0.5}, {0.5, 0.5}, {4, 0}, 1.0, 1.0, 0.5, {}};
  Scene s = ground_and(box, 120);
  s.bodies[0].friction = 0.5;
  for (const EngineDef* e : self_contained_engines()) {
    SCOPED_TRACE(e->name);
    const EngineSpec spec = parse_engine_spec(e->name);
    if (!e->capabilities(spec).friction) {
      EXPECT_NE(missing_capability(spec, s).find("has no friction"), std::string::npos);
      EXPECT_THROW(make_engine(spec, s), InputError);
      continue;
    }
    const auto path = trajectory(spec, s);
    EXPECT_NEAR(path.back().position[1].x, 1.6, 0.05);
    EXPECT_NEAR(path.back().velocity[1].x, 0.0, 1e-6);
  }
}

// Restitution: a box dropped from 1 m above the ground with restitution 0.5 (combined as the
// larger of the two) climbs back towards 0.25 m; we ask only that it leaves the ground by more
// than 0.1 m after first touching it, which no inelastic contact does.
TEST(Capabilities, RestitutionIsThereWhereClaimedAndRefusedWhereNot) {
  SceneBody box{"box", BodyKind::kDynamic, {0, 1.5}, {0.5, 0.5}, {}, 1.0, 1.0, {}, 0.5};
  const Scene s = ground_and(box, 90);
  for (const EngineDef* e : self_contained_engines()) {
    SCOPED_TRACE(e->name);
    const EngineSpec spec = parse_engine_spec(e->name);
    if (!e->capabilities(spec).restitution) {
      EXPECT_NE(missing_capability(spec, s).find("does not bounce"), std::string::npos);
      continue;
    }
    const auto path = trajectory(spec, s);
    bool touched = false;
    double climb = 0.0;
    for (const BodyState& st : path) {
      const double y = st.position[1].y;
      touched = touched || y < 0.52;
      if (touched) climb = std::max(climb, y - 0.5);
    }
    EXPECT_TRUE(touched);
    EXPECT_GT(climb, 0.1);
  }
}

// Kinematic bodies keep their velocity: after n steps a lift at 1 m/s has risen n dt metres.
TEST(Capabilities, KinematicBodiesMoveAtTheirVelocity) {
  SceneBody lift{"lift", BodyKind::kKinematic, {5, 1}, {1, 0.25}, {0, 1}, 0.0, 1.0, {}, {}};
  const Scene s = ground_and(lift, 60);
  for (const EngineDef* e : self_contained_engines()) {
    SCOPED_TRACE(e->name);
    const EngineSpec spec = parse_engine_spec(e->name);
    if (!e->capabilities(spec).kinematic) {
      EXPECT_NE(missing_capability(spec, s).find("no kinematic bodies"), std::string::npos);
      continue;
    }
    // 1e-5 m: positions held in single precision (float ulp 2.4e-7 m near 2 m, over 60 steps).
    EXPECT_NEAR(trajectory(spec, s).back().position[1].y, 1.0 + 60 * s.dt, 1e-5);
  }
}

// A drive that holds x only: the body walks at 3 m/s and falls freely. Engines integrate in
// different orders (velocity then position gives y0 - g dt^2 n (n + 1) / 2, position then velocity
// y0 - g dt^2 n (n - 1) / 2), so the fall is checked against the exact y0 - g t^2 / 2 within a
// first-order integrator's error, g dt t / 2 (4.2 cm here), and x within single precision.
TEST(Capabilities, AxisDrivesHoldOneAxisAndLeaveTheOtherToGravity) {
  SceneBody walker{"walker", BodyKind::kDynamic, {0, 20}, {0.5, 0.5}, {}, 1.0, 1.0, {}, {}};
  Scene s = ground_and(walker, 30);
  Driver d;
  d.body = 1;
  d.velocity = {3, 0};
  d.hold_y = false;
  s.drivers.push_back(d);
  for (const EngineDef* e : self_contained_engines()) {
    SCOPED_TRACE(e->name);
    const EngineSpec spec = parse_engine_spec(e->name);
    if (!e->capabilities(spec).axis_drives) {
      EXPECT_NE(missing_capability(spec, s).find("leaves y free"), std::string::npos);
      continue;
    }
    const BodyState last = trajectory(spec, s).back();
    const int n = s.steps;
    const double t = n * s.dt;
    EXPECT_NEAR(last.position[1].x, 3.0 * t, 1e-5);
    EXPECT_NEAR(last.position[1].y, 20.0 - 10.0 * t * t / 2.0, 10.0 * s.dt * t / 2.0 + 1e-5);
  }
}

TEST(Capabilities, RotationIsRefusedByEnginesThatCannotTurnBodies) {
  SceneBody box{"box", BodyKind::kDynamic, {0, 0.5}, {0.5, 0.5}, {}, 1.0, 1.0, {}, {}};
  Scene s = ground_and(box, 10);
  s.rotation = true;
  for (const EngineDef* e : self_contained_engines()) {
    SCOPED_TRACE(e->name);
    const EngineSpec spec = parse_engine_spec(e->name);
    if (e->capabilities(spec).rotation) {
      EXPECT_NO_THROW(trajectory(spec, s));
    } else {
      EXPECT_NE(missing_capability(spec, s).find("cannot turn bodies"), std::string::npos);
    }
  }
}

}  // namespace
}  // namespace chainbench
