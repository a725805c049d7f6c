// SPDX-License-Identifier: MIT
// The 2014 variant keeps the quirks of docs/algorithm-2014.md §4; these pin them down against
// hand-worked cases, next to what modern does instead.
#include "world_helpers.h"

#include <gtest/gtest.h>

namespace chain::testing {
namespace {

constexpr double kDt = 1.0 / 60.0;

// docs/algorithm-2014.md §3.4, Quirk 1: a 100 x 40 box over a 10 x 20 static one near its left
// edge is pushed 30 along y, though 15 along x would separate them. In y-up units (1 px = 1 m): A
// spans x [0,100], y [-40,0]; B is static.
TEST(Seed2014, PushDirectionComesFromEdgesNotCentres) {
  auto resolve = [](Variant v) {
    World w(world_def(v, VelocityRule::kZero, {0.0, 0.0}));
    BodyDef a = dynamic_box(50.0, -20.0);
    a.half_extents = {50.0, 20.0};
    const BodyId id = w.create_body(a);
    w.create_body(static_box(10.0, -20.0, 5.0, 10.0));
    w.step(kDt);
    return w.position(id);
  };
  const Vec2 seed = resolve(Variant::kSeed2014);
  EXPECT_FLOAT_EQ(seed.x, 50.0);
  EXPECT_FLOAT_EQ(seed.y, -20.0 + 30.0);  // y-down (0,-30) is 30 up
  const Vec2 modern = resolve(Variant::kModern);
  EXPECT_FLOAT_EQ(modern.x, 50.0 + 15.0);  // the shortest way out
  EXPECT_FLOAT_EQ(modern.y, -20.0);
}

TEST(Seed2014, TouchingIsNotPushing) {
  for (const Variant v : {Variant::kModern, Variant::kSeed2014}) {
    World w(world_def(v, VelocityRule::kZero, {0.0, 0.0}));
    const BodyId a = w.create_body(dynamic_box(0.0, 0.0));
    const BodyId b = w.create_body(dynamic_box(1.0, 0.0));
    w.step(kDt);
    EXPECT_FLOAT_EQ(w.position(a).x, 0.0);
    EXPECT_FLOAT_EQ(w.position(b).x, 1.0);
    EXPECT_EQ(w.touching_flags(a), 0u);  // flags come from pushes, as in the 2014 engine
  }
}

// docs/algorithm-2014.md §2.5, Quirk 4 (example §3.6): every dynamic body takes its turn as `a`, so
// each dynamic pair is met twice; a fresh overlap between two free boxes is split evenly either
// way.
TEST(Seed2014, EqualMassesSplitAnOverlapEvenly) {
  World w(world_def(Variant::kSeed2014, VelocityRule::kZero, {0.0, 0.0}));
  const BodyId a = w.create_body(dynamic_box(0.0, 0.0));
  const BodyId b = w.create_body(dynamic_box(0.8, 0.0));
  w.step(kDt);
  EXPECT_FLOAT_EQ(w.position(a).x, -0.1);
  EXPECT_FLOAT_EQ(w.position(b).x, 0.9);
}

// docs/algorithm-2014.md Quirk 3 (§3.7): the grid is built once per step and never updated. A body
// pushed further than the grid's reach during the step is not met by the bodies near its new place
// until next step.
TEST(Seed2014, StaleGridMissesPairsCreatedByALongPush) {
  auto overlap_after_one_step = [](Variant v) {
    World w(world_def(v, VelocityRule::kZero, {0.0, 0.0}));
    // A heavy box created deep inside a light one shoves it 1.5 m right, onto a third box
    // two grid cells from where the grid saw it.
    BodyDef heavy = dynamic_box(0.0, 0.0, 2.0, 1000.0);
    w.create_body(heavy);
    const BodyId light = w.create_body(dynamic_box(1.0, 0.0));
    const BodyId far = w.create_body(dynamic_box(3.2, 0.0));
    w.step(kDt);
    return 1.0 - (w.position(far).x - w.position(light).x);
  };
  EXPECT_GT(overlap_after_one_step(Variant::kSeed2014), 0.1);
  EXPECT_LE(overlap_after_one_step(Variant::kModern), 1e-9);
}

}  // namespace
}  // namespace chain::testing
