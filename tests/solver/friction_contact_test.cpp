// SPDX-License-Identifier: MIT
// Friction's share of a step's motion (the trapezoidal rule: half the velocity it took off, times
// dt; solver/src/friction.h) never moves a body into another: not a crate a platform carries
// into a wall, not a crate slowed back into the pusher behind it, at any time step.
#include "world_helpers.h"

#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

namespace chain::testing {
namespace {

BodyDef rough(BodyDef d, double friction) {
  d.friction = friction;
  return d;
}

const char* rule_name(VelocityRule r) {
  return r == VelocityRule::kZero ? "zero" : "inelastic";
}

// Issue 23: a rough crate (mu = 1) carried at 2 m/s by a platform into a static wall ended
// mu g dt^2 / 2 = 1.4 mm inside it at 60 Hz, friction having moved it on after the wall's push.
// It stops touching the wall, x = 1 - 0.25, while the platform slides on under it, and is never
// inside it after any step.
TEST(FrictionContact, ACrateCarriedIntoAWallStopsAgainstIt) {
  for (const VelocityRule rule : {VelocityRule::kZero, VelocityRule::kInelastic}) {
    for (const double mu : {0.5, 1.0, 5.0}) {
      for (const double dt : {1.0 / 240.0, 1.0 / 60.0, 1.0 / 30.0, 0.1}) {
        World w(world_def(Variant::kModern, rule));
        w.create_body(rough(kinematic_box(0.0, -0.5, 40.0, 0.5, {2.0, 0.0}), mu));
        const BodyId wall = w.create_body(static_box(1.5, 1.0, 0.5, 1.0));
        const BodyId crate = w.create_body(rough(dynamic_box(0.0, 0.25, 0.25, 5.0), mu));
        const std::string what = std::string(rule_name(rule)) + " mu " + std::to_string(mu) +
                                 " dt " + std::to_string(dt);
        for (int s = 0; s < static_cast<int>(3.0 / dt); ++s) {
          w.step(dt);
          ASSERT_LE(max_penetration(w, {wall, crate}, {{0.5, 1.0}, {0.25, 0.25}}), 1e-9)
              << what << " step " << s;
        }
        EXPECT_NEAR(w.position(crate).x, 0.75, 1e-9) << what;
        EXPECT_NEAR(w.position(crate).y, 0.25, 1e-9) << what;
      }
    }
  }
}

// A driven pusher shoving a rough crate along a rough floor (mu = 0.5): the crate, slowed by the
// floor, used to be moved back into the pusher, 0.0875 m at dt 0.35 s and through it at 1 s. It
// keeps touching it, one crate edge ahead, and the pusher is never inside it.
TEST(FrictionContact, ACrateSlowedByTheFloorStaysAheadOfItsPusher) {
  for (const double dt : {1.0 / 60.0, 0.1, 0.2, 0.35, 0.5, 1.0}) {
    World w(world_def(Variant::kModern, VelocityRule::kInelastic));
    const BodyId floor = w.create_body(rough(static_box(0.0, -1.0, 100.0, 1.0), 0.5));
    const BodyId pusher = w.create_body(rough(dynamic_box(-1.0, 0.5, 0.5, 80.0), 0.5));
    const BodyId crate = w.create_body(rough(dynamic_box(0.0, 0.5, 0.5, 10.0), 0.5));
    w.set_drive(pusher, {2.0, 0.0}, DriveAxes::kX);
    const std::vector<Vec2> half = {{100.0, 1.0}, {0.5, 0.5}, {0.5, 0.5}};
    for (int s = 0; s < static_cast<int>(3.0 / dt); ++s) {
      w.step(dt);
      ASSERT_LE(max_penetration(w, {floor, pusher, crate}, half), 1e-9) << dt << " step " << s;
    }
    EXPECT_NEAR(w.position(crate).x - w.position(pusher).x, 1.0, 1e-9) << dt;
  }
}

// The kind: a driven pusher shoving a row of rough crates of mixed sizes and masses, some of them
// sliding towards it or away, along a rough floor into a static wall, at several time steps and
// coefficients. After every step no two bodies overlap: whatever friction moved, it moved into
// nothing. The worlds take up to 1,000 contact passes a step: with the default 4, a mixed row at
// dt 0.1 s can end a step with pushes still unresolved, friction or not (docs/limits.md).
TEST(FrictionContact, NoStepLeavesARoughRowInsideItself) {
  int steps = 0;
  for (const double dt : {1.0 / 60.0, 1.0 / 20.0, 0.1}) {
    for (std::uint32_t seed = 1; seed <= 8; ++seed) {
      std::mt19937 rng(seed);
      std::uniform_real_distribution<double> unit(0.0, 1.0);
      const double mu = 0.2 + 2.0 * unit(rng);
      WorldDef def = world_def(Variant::kModern, VelocityRule::kInelastic);
      def.max_passes = 1000;
      World w(def);
      std::vector<BodyId> ids;
      std::vector<Vec2> half;
      auto add = [&](BodyDef d) {
        half.push_back(d.half_extents);
        return ids.emplace_back(w.create_body(d));
      };
      add(rough(static_box(0.0, -1.0, 30.0, 1.0), mu));  // floor
      add(rough(static_box(12.5, 5.0, 0.5, 5.0), mu));   // wall
      const BodyId pusher = add(rough(dynamic_box(-10.0, 0.5, 0.5, 50.0), mu));
      w.set_drive(pusher, {3.0, 0.0}, DriveAxes::kX);
      double x = -9.5;
      for (int i = 0; i < 12; ++i) {
        BodyDef d = rough(dynamic_box(0.0, 0.0, 0.5, 1.0 + 9.0 * unit(rng)), mu * unit(rng) * 2.0);
        d.half_extents = {0.2 + 0.3 * unit(rng), 0.2 + 0.3 * unit(rng)};
        x += d.half_extents.x + 0.3 * unit(rng);
        d.center = {x, d.half_extents.y};
        x += d.half_extents.x;
        d.velocity = {6.0 * (unit(rng) - 0.5), 0.0};
        add(d);
      }
      for (int s = 0; s < static_cast<int>(4.0 / dt); ++s, ++steps) {
        w.step(dt);
        ASSERT_LE(max_penetration(w, ids, half), 1e-7) << dt << " seed " << seed << " step " << s;
      }
    }
  }
  EXPECT_GT(steps, 3 * 8 * 40);
}

}  // namespace
}  // namespace chain::testing
