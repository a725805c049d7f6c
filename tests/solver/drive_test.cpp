// SPDX-License-Identifier: MIT
// Per-axis drives: a drive holds the velocity components it is given and leaves the others to
// gravity and contacts, as a character controller sets a walking speed and lets the body fall.
#include "world_helpers.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace chain::testing {
namespace {

constexpr double kDt = 1.0 / 60.0;
constexpr double kG = 10.0;

// A 0.5 m box walks at 4 m/s along x off a ledge whose top is y = 0 and right edge x = 0. Its left
// edge is at -1.24 + n / 15 after step n, so it rests on the ledge (y = 0.25, vy = 0) through step
// m - 1 = 18 and is free from step m = 19 on. From there it falls as integration drops a free body
// (symplectic Euler: k steps of free fall drop it g dt^2 k (k + 1) / 2), with x = x0 + 4 n dt all
// the way: ballistic. That is the continuous parabola y = 0.25 - g (t - t0)^2 / 2 from
// t0 = 0.31 s (when the edge is passed) up to the discretisation's own error: with ts = 0.3 s the
// last supported step and tau = t - ts, the two differ by g (tau dt + 2 tau (t0 - ts) -
// (t0 - ts)^2) / 2, under 1.5 g dt tau.
TEST(Drive, WalkingOffALedgeAlongXFallsBallistically) {
  for (const Variant v : {Variant::kModern, Variant::kSeed2014}) {
    for (const VelocityRule rule : {VelocityRule::kZero, VelocityRule::kInelastic}) {
      World w(world_def(v, rule));
      w.create_body(static_box(-5.0, -0.5, 5.0, 0.5));
      const double x0 = -0.99;
      const BodyId id = w.create_body(dynamic_box(x0, 0.25, 0.25));
      w.set_drive(id, {4.0, 0.0}, DriveAxes::kX);
      const int m = 19;
      for (int n = 1; n <= 60; ++n) {
        w.step(kDt);
        const Vec2 p = w.position(id);
        ASSERT_NEAR(p.x, x0 + 4.0 * n * kDt, 1e-9) << variant_name(v) << " step " << n;
        const int k = n < m ? 0 : n - m + 1;  // steps of free fall so far
        ASSERT_NEAR(p.y, 0.25 - kG * kDt * kDt * k * (k + 1) / 2.0, 1e-9)
            << variant_name(v) << " step " << n;
        ASSERT_NEAR(w.velocity(id).y, -kG * kDt * k, 1e-9) << variant_name(v) << " step " << n;
        ASSERT_EQ(w.velocity(id).x, 4.0);
        const double t = n * kDt, t0 = 1.24 / 4.0, ts = (m - 1) * kDt;
        if (t > t0) {
          const double parabola = 0.25 - 0.5 * kG * (t - t0) * (t - t0);
          ASSERT_NEAR(p.y, parabola, 1.5 * kG * kDt * (t - ts)) << "step " << n;
        }
      }
    }
  }
}

// The two-argument drive holds both components: the driven box does not fall off the ledge, it
// only sinks by the one step of gravity the drive lets act each step (g dt^2 a step).
TEST(Drive, ADriveOnBothAxesHoldsTheBodyUp) {
  World w(world_def(Variant::kModern, VelocityRule::kInelastic));
  w.create_body(static_box(-5.0, -0.5, 5.0, 0.5));
  const BodyId id = w.create_body(dynamic_box(-0.99, 0.25, 0.25));
  w.set_drive(id, {4.0, 0.0});
  for (int n = 1; n <= 60; ++n)
    w.step(kDt);
  EXPECT_NEAR(w.position(id).y, 0.25 - kG * kDt * kDt * (60 - 19 + 1), 1e-9);
}

// Holding y only: a dynamic lift body rises at its drive speed while a pusher moves it sideways.
TEST(Drive, HoldingYLeavesXToContacts) {
  World w(world_def(Variant::kModern, VelocityRule::kInelastic, {0.0, -10.0}));
  const BodyId lifted = w.create_body(dynamic_box(1.0, 0.0));
  const BodyId pusher = w.create_body(dynamic_box(0.0, 0.0));
  w.set_drive(lifted, {0.0, 1.0}, DriveAxes::kY);
  w.set_drive(pusher, {2.0, 1.0});
  for (int n = 1; n <= 30; ++n) {
    w.step(kDt);
    ASSERT_NEAR(w.position(lifted).y, n * kDt * (1.0 - kG * kDt), 1e-9);
  }
  EXPECT_GT(w.position(lifted).x, 1.0 + 0.4);  // pushed along at half the pusher's speed, or more
}

// A kinematic body driven along x keeps its own y velocity.
TEST(Drive, KinematicBodyDrivenAlongXKeepsItsYVelocity) {
  World w(world_def(Variant::kModern, VelocityRule::kInelastic));
  const BodyId lift = w.create_body(kinematic_box(0.0, 0.0, 1.0, 0.1, {0.0, 0.5}));
  w.set_drive(lift, {3.0, 7.0}, DriveAxes::kX);
  for (int n = 0; n < 10; ++n)
    w.step(kDt);
  EXPECT_EQ(w.velocity(lift).x, 3.0);
  EXPECT_EQ(w.velocity(lift).y, 0.5);
}

TEST(Drive, BadAxesAndComponentsAreRefused) {
  World w;
  const BodyId box = w.create_body(dynamic_box(0.0, 0.0));
  EXPECT_THROW(w.set_drive(box, {1.0, 0.0}, static_cast<DriveAxes>(0)), std::invalid_argument);
  EXPECT_THROW(w.set_drive(box, {1.0, 0.0}, static_cast<DriveAxes>(4)), std::invalid_argument);
  EXPECT_THROW(w.set_drive(box, {2e6, 0.0}, DriveAxes::kX), std::invalid_argument);
  // The component a drive does not hold is not looked at.
  EXPECT_NO_THROW(w.set_drive(box, {1.0, std::nan("")}, DriveAxes::kX));
  const BodyId ground = w.create_body(static_box(0.0, -5.0, 1.0, 1.0));
  EXPECT_THROW(w.set_drive(ground, {1.0, 0.0}, DriveAxes::kX), std::invalid_argument);
}

}  // namespace
}  // namespace chain::testing
