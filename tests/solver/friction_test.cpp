// SPDX-License-Identifier: MIT
// Coulomb friction (modern variant, solver/src/friction.h), against the analytic answers: a body
// slipping on a surface decelerates at mu g relative to it, so it slips v^2 / (2 mu g) before it
// moves with it. Positions are checked within 2 cm after 1 s, velocities to rounding.
#include "world_helpers.h"

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <vector>

namespace chain::testing {
namespace {

constexpr double kDt = 1.0 / 60.0;

const char* rule_name(VelocityRule r) {
  return r == VelocityRule::kZero ? "zero" : "inelastic";
}

BodyDef rough(BodyDef d, double friction) {
  d.friction = friction;
  return d;
}

// Issue 5: a crate on a kinematic platform moving sideways at 2 m/s. Friction 1 on both (mu = 1):
// the crate slips 2^2 / (2 * 1 * 10) = 0.2 m behind the platform in 0.2 s, then rides at 2 m/s.
TEST(Friction, CrateOnAMovingPlatformSlipsThenRides) {
  for (const VelocityRule rule : {VelocityRule::kZero, VelocityRule::kInelastic}) {
    World w(world_def(Variant::kModern, rule));
    const BodyId platform =
        w.create_body(rough(kinematic_box(0.0, -0.5, 10.0, 0.5, {2.0, 0.0}), 1.0));
    const BodyId crate = w.create_body(rough(dynamic_box(0.0, 0.25, 0.25, 5.0), 1.0));
    for (int s = 0; s < 60; ++s)
      w.step(kDt);
    const double slip = w.position(platform).x - w.position(crate).x;
    EXPECT_NEAR(slip, 0.2, 0.02) << rule_name(rule);
    EXPECT_NEAR(w.velocity(crate).x, 2.0, 1e-12) << rule_name(rule);
    EXPECT_NEAR(w.position(crate).y, 0.25, 1e-9) << rule_name(rule);
  }
}

// Without friction the platform slides out from under the crate, which falls off its end.
TEST(Friction, FrictionlessCrateStaysBehindAndFallsOff) {
  World w(world_def(Variant::kModern, VelocityRule::kInelastic));
  w.create_body(kinematic_box(0.0, -0.5, 1.0, 0.5, {2.0, 0.0}));
  const BodyId crate = w.create_body(dynamic_box(0.0, 0.25, 0.25));
  for (int s = 0; s < 120; ++s)
    w.step(kDt);
  EXPECT_EQ(w.position(crate).x, 0.0);
  EXPECT_LT(w.position(crate).y, 0.0);
}

// A crate sliding at 3 m/s on a rough floor (mu = 0.5) stops after 3^2 / (2 * 0.5 * 10) = 0.9 m,
// in 0.6 s.
TEST(Friction, SlidingCrateStopsWhereCoulombSays) {
  for (const VelocityRule rule : {VelocityRule::kZero, VelocityRule::kInelastic}) {
    World w(world_def(Variant::kModern, rule));
    w.create_body(rough(static_box(0.0, -1.0, 50.0, 1.0), 0.5));
    BodyDef crate = rough(dynamic_box(0.0, 0.25, 0.25), 0.5);
    crate.velocity = {3.0, 0.0};
    const BodyId id = w.create_body(crate);
    for (int s = 0; s < 60; ++s)
      w.step(kDt);
    EXPECT_NEAR(w.position(id).x, 0.9, 0.02) << rule_name(rule);
    EXPECT_EQ(w.velocity(id).x, 0.0) << rule_name(rule);
  }
}

// Friction with a body of friction 0 is none: sqrt(0.5 * 0) = 0, as Box2D mixes it.
TEST(Friction, CoefficientsMixAsTheSquareRootOfTheProduct) {
  auto slide = [](double floor_friction, double crate_friction) {
    World w(world_def(Variant::kModern, VelocityRule::kInelastic));
    w.create_body(rough(static_box(0.0, -1.0, 50.0, 1.0), floor_friction));
    BodyDef crate = rough(dynamic_box(0.0, 0.25, 0.25), crate_friction);
    crate.velocity = {3.0, 0.0};
    const BodyId id = w.create_body(crate);
    for (int s = 0; s < 60; ++s)
      w.step(kDt);
    return w.position(id).x;
  };
  EXPECT_NEAR(slide(0.5, 0.0), 3.0, 1e-12);
  // mu = sqrt(0.25 * 1) = 0.5: the same stop as 0.5 on both.
  EXPECT_NEAR(slide(0.25, 1.0), slide(0.5, 0.5), 1e-12);
}

// A crate pushed along a rough floor by a driven pusher slows and stops once the drive stops;
// frictionless, it glides on at the speed the pushes gave it.
TEST(Friction, PushedCrateSlowsWhenTheDriveStops) {
  for (const double mu : {0.0, 0.5}) {
    World w(world_def(Variant::kModern, VelocityRule::kInelastic));
    w.create_body(rough(static_box(0.0, -1.0, 50.0, 1.0), mu));
    const BodyId pusher = w.create_body(rough(dynamic_box(0.0, 0.25, 0.25), mu));
    const BodyId crate = w.create_body(rough(dynamic_box(0.5, 0.25, 0.25), mu));
    w.set_drive(pusher, {2.0, 0.0}, DriveAxes::kX);
    for (int s = 0; s < 30; ++s)
      w.step(kDt);
    EXPECT_GT(w.position(crate).x, 0.5 + 0.9) << mu;  // pushed along at the drive's speed
    w.clear_drive(pusher);
    double speed = w.velocity(crate).x;
    EXPECT_GT(speed, 1.0) << mu;
    for (int s = 0; s < 60; ++s) {
      w.step(kDt);
      if (mu > 0.0) {
        ASSERT_LE(w.velocity(crate).x, speed) << "step " << s;
      }
      speed = w.velocity(crate).x;
    }
    if (mu > 0.0) {
      EXPECT_EQ(w.velocity(crate).x, 0.0);
      EXPECT_EQ(w.velocity(pusher).x, 0.0);
    } else {
      EXPECT_GT(w.velocity(crate).x, 1.0);
    }
  }
}

// A stack of three crates on the moving platform is carried as a whole: the bottom contact's
// normal impulse carries the whole stack's weight, so friction there accelerates all three at
// mu g, and every crate slips the same 0.2 m.
TEST(Friction, StackOnAMovingPlatformIsCarriedAsAWhole) {
  for (const VelocityRule rule : {VelocityRule::kZero, VelocityRule::kInelastic}) {
    World w(world_def(Variant::kModern, rule));
    const BodyId platform =
        w.create_body(rough(kinematic_box(0.0, -0.5, 10.0, 0.5, {2.0, 0.0}), 1.0));
    std::vector<BodyId> stack;
    for (int i = 0; i < 3; ++i)
      stack.push_back(w.create_body(rough(dynamic_box(0.0, 0.25 + 0.5 * i, 0.25), 1.0)));
    for (int s = 0; s < 60; ++s)
      w.step(kDt);
    for (int i = 0; i < 3; ++i) {
      const BodyId id = stack[static_cast<std::size_t>(i)];
      EXPECT_NEAR(w.position(platform).x - w.position(id).x, 0.2, 0.02)
          << rule_name(rule) << " crate " << i;
      EXPECT_NEAR(w.position(id).x, w.position(stack[0]).x, 1e-3) << rule_name(rule);
      EXPECT_NEAR(w.velocity(id).x, 2.0, 1e-9) << rule_name(rule) << " crate " << i;
      EXPECT_NEAR(w.position(id).y, 0.25 + 0.5 * i, 1e-9) << rule_name(rule);
    }
  }
}

// A character walking at a held speed over a rough floor keeps that speed exactly: friction never
// changes a component a drive holds.
TEST(Friction, DriveHoldsItsSpeedOnARoughFloor) {
  World w(world_def(Variant::kModern, VelocityRule::kInelastic));
  w.create_body(rough(static_box(0.0, -1.0, 50.0, 1.0), 1.0));
  const BodyId walker = w.create_body(rough(dynamic_box(0.0, 0.25, 0.25), 1.0));
  w.set_drive(walker, {4.0, 0.0}, DriveAxes::kX);
  for (int s = 1; s <= 60; ++s) {
    w.step(kDt);
    ASSERT_NEAR(w.position(walker).x, 4.0 * s * kDt, 1e-9);
  }
}

// Zero friction everywhere that matters changes nothing, to the bit: friction on the floor alone
// mixes to 0 with the frictionless boxes.
TEST(Friction, ZeroFrictionChangesNothingToTheBit) {
  auto run = [](double floor_friction) {
    World w(world_def(Variant::kModern, VelocityRule::kInelastic));
    w.create_body(rough(static_box(0.0, -1.0, 50.0, 1.0), floor_friction));
    std::vector<BodyId> ids;
    for (int i = 0; i < 6; ++i) {
      BodyDef d = dynamic_box(0.3 * i, 0.5 + 1.1 * i);
      d.velocity = {1.0 - 0.4 * i, 0.0};
      ids.push_back(w.create_body(d));
    }
    for (int s = 0; s < 120; ++s)
      w.step(kDt);
    std::vector<std::uint64_t> bits;
    for (const BodyId id : ids) {
      bits.push_back(std::bit_cast<std::uint64_t>(w.position(id).x));
      bits.push_back(std::bit_cast<std::uint64_t>(w.position(id).y));
      bits.push_back(std::bit_cast<std::uint64_t>(w.velocity(id).x));
    }
    return bits;
  };
  EXPECT_EQ(run(0.0), run(0.7));
}

// seed2014 had no friction, and keeps none.
TEST(Friction, Seed2014IgnoresIt) {
  World w(world_def(Variant::kSeed2014, VelocityRule::kZero));
  w.create_body(rough(static_box(0.0, -1.0, 50.0, 1.0), 1.0));
  BodyDef crate = rough(dynamic_box(0.0, 0.25, 0.25), 1.0);
  crate.velocity = {3.0, 0.0};
  const BodyId id = w.create_body(crate);
  for (int s = 0; s < 60; ++s)
    w.step(kDt);
  EXPECT_EQ(w.velocity(id).x, 3.0);
}

}  // namespace
}  // namespace chain::testing
