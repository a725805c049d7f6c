// SPDX-License-Identifier: MIT
// Conveyors (BodyDef::surface_velocity): friction acts on what touches a static or kinematic body
// as if its surface moved at that velocity on top of the body's own, so a crate on a belt slips
// v^2 / (2 mu g) and then rides at the belt's speed, as on a platform moving at it.
#include "world_helpers.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

namespace chain::testing {
namespace {

constexpr double kDt = 1.0 / 60.0;

BodyDef belt(double speed, double mu) {
  BodyDef d = static_box(0.0, -0.5, 20.0, 0.5);
  d.friction = mu;
  d.surface_velocity = {speed, 0.0};
  return d;
}

BodyDef crate(double x, double mu) {
  BodyDef d = dynamic_box(x, 0.25, 0.25, 5.0);
  d.friction = mu;
  return d;
}

// Issue 23: a crate (mu = 1 with the belt) dropped at rest on a belt moving at 2 m/s reaches
// 2 m/s after 2 / (mu g) = 0.2 s, having slipped 0.2 m behind the belt: after 1 s it is at
// 2 * 1 - 0.2 = 1.8 m (within 2 cm: one step's travel), riding at exactly 2 m/s. Backwards the
// same, mirrored; at mu = 0.5 it slips 0.4 m.
TEST(Conveyor, ACrateSlipsThenRidesAtTheBeltsSpeed) {
  for (const VelocityRule rule : {VelocityRule::kZero, VelocityRule::kInelastic}) {
    for (const double speed : {2.0, -2.0}) {
      for (const double mu : {1.0, 0.5}) {
        World w(world_def(Variant::kModern, rule));
        w.create_body(belt(speed, mu));
        const BodyId id = w.create_body(crate(0.0, mu));
        for (int s = 0; s < 60; ++s)
          w.step(kDt);
        const double slip = speed * speed / (2.0 * mu * 10.0);
        EXPECT_NEAR(w.position(id).x, speed * 1.0 - std::copysign(slip, speed), 0.02)
            << speed << " " << mu;
        EXPECT_NEAR(w.velocity(id).x, speed, 1e-12) << speed << " " << mu;
        EXPECT_NEAR(w.position(id).y, 0.25, 1e-9);
      }
    }
  }
}

// A belt's speed adds to its body's: a crate on a kinematic platform moving at 1 m/s whose belt
// runs at 1 m/s rides at 2 m/s.
TEST(Conveyor, ABeltOnAMovingPlatformAddsToItsSpeed) {
  World w(world_def(Variant::kModern, VelocityRule::kInelastic));
  BodyDef platform = kinematic_box(0.0, -0.5, 50.0, 0.5, {1.0, 0.0});
  platform.friction = 1.0;
  platform.surface_velocity = {1.0, 0.0};
  w.create_body(platform);
  const BodyId id = w.create_body(crate(0.0, 1.0));
  for (int s = 0; s < 60; ++s)
    w.step(kDt);
  EXPECT_NEAR(w.velocity(id).x, 2.0, 1e-12);
}

// Without friction the belt runs under the crate, which stays where it is, to the bit; a drive's
// held speed is never changed by it; 2014's variant has no friction and ignores belts.
TEST(Conveyor, NoFrictionNoDriveNoEffect) {
  World smooth(world_def(Variant::kModern, VelocityRule::kInelastic));
  smooth.create_body(belt(3.0, 0.0));
  const BodyId still = smooth.create_body(crate(1.0, 0.0));
  World walker(world_def(Variant::kModern, VelocityRule::kInelastic));
  walker.create_body(belt(3.0, 1.0));
  const BodyId held = walker.create_body(crate(1.0, 1.0));
  walker.set_drive(held, {0.5, 0.0}, DriveAxes::kX);
  World seed(world_def(Variant::kSeed2014, VelocityRule::kZero));
  seed.create_body(belt(3.0, 1.0));
  const BodyId old = seed.create_body(crate(1.0, 1.0));
  for (int s = 0; s < 60; ++s) {
    smooth.step(kDt);
    walker.step(kDt);
    seed.step(kDt);
    ASSERT_EQ(walker.velocity(held).x, 0.5) << s;
  }
  EXPECT_EQ(smooth.position(still).x, 1.0);
  EXPECT_EQ(smooth.velocity(still).x, 0.0);
  EXPECT_EQ(seed.position(old).x, 1.0);
}

TEST(Conveyor, ABeltIsForStaticAndKinematicBodiesOnly) {
  World w(world_def(Variant::kModern, VelocityRule::kInelastic));
  BodyDef d = crate(0.0, 1.0);
  d.surface_velocity = {1.0, 0.0};
  EXPECT_THROW(w.create_body(d), std::invalid_argument);
  BodyDef b = belt(std::numeric_limits<double>::quiet_NaN(), 1.0);
  EXPECT_THROW(w.create_body(b), std::invalid_argument);
  b = belt(2e6, 1.0);
  EXPECT_THROW(w.create_body(b), std::invalid_argument);
  EXPECT_EQ(w.body_count(), 0u);
}

}  // namespace
}  // namespace chain::testing
