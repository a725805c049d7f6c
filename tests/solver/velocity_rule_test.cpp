// SPDX-License-Identifier: MIT
// Velocity response: momentum where the inelastic rule must conserve it, the zero rule's
// stopping, restitution, and kinematic bodies that carry what they push.
#include "world_helpers.h"

#include <gtest/gtest.h>

#include <vector>

namespace chain::testing {
namespace {

constexpr double kDt = 1.0 / 60.0;

double momentum_x(const World& w, const std::vector<BodyId>& ids, const std::vector<double>& mass) {
  double p = 0.0;
  for (std::size_t i = 0; i < ids.size(); ++i)
    p += mass[i] * w.velocity(ids[i]).x;
  return p;
}

double center_of_mass_x(const World& w, const std::vector<BodyId>& ids,
                        const std::vector<double>& mass) {
  double m = 0.0, mx = 0.0;
  for (std::size_t i = 0; i < ids.size(); ++i) {
    m += mass[i];
    mx += mass[i] * w.position(ids[i]).x;
  }
  return mx / m;
}

TEST(InelasticRule, MovingBoxHittingAFreeBoxConservesMomentum) {
  for (const Variant v : {Variant::kModern, Variant::kSeed2014}) {
    World w(world_def(v, VelocityRule::kInelastic, {0.0, 0.0}));
    BodyDef mover = dynamic_box(0.0, 0.0, 0.5, 1.0);
    mover.velocity = {3.0, 0.0};
    const std::vector<double> mass = {1.0, 2.0};
    const std::vector<BodyId> ids = {w.create_body(mover),
                                     w.create_body(dynamic_box(2.0, 0.3, 0.5, 2.0))};
    const double before = momentum_x(w, ids, mass);
    for (int s = 0; s < 60; ++s) {
      w.step(kDt);
      ASSERT_NEAR(momentum_x(w, ids, mass), before, 1e-12 * before)
          << variant_name(v) << " step " << s;
    }
    // Perfectly inelastic: they leave together at p / (m1 + m2).
    EXPECT_NEAR(w.velocity(ids[0]).x, 1.0, 1e-12) << variant_name(v);
    EXPECT_NEAR(w.velocity(ids[1]).x, 1.0, 1e-12) << variant_name(v);
  }
}

TEST(InelasticRule, BoxHittingATouchingRowSharesMomentumWithTheWholeRow) {
  World w(world_def(Variant::kModern, VelocityRule::kInelastic, {0.0, 0.0}));
  BodyDef mover = dynamic_box(-3.0, 0.0, 0.5, 2.0);
  mover.velocity = {4.0, 0.0};
  std::vector<BodyId> ids = {w.create_body(mover)};
  std::vector<double> mass = {2.0};
  for (int i = 0; i < 4; ++i) {
    ids.push_back(
        w.create_body(dynamic_box(static_cast<double>(i), 0.0, 0.5, 0.5 + static_cast<double>(i))));
    mass.push_back(0.5 + static_cast<double>(i));
  }
  const double before = momentum_x(w, ids, mass);
  for (int s = 0; s < 120; ++s)
    w.step(kDt);
  EXPECT_NEAR(momentum_x(w, ids, mass), before, 1e-12 * before);
  const double shared = before / (2.0 + 0.5 + 1.5 + 2.5 + 3.5);
  for (const BodyId id : ids)
    EXPECT_NEAR(w.velocity(id).x, shared, 1e-12);
}

// Splitting a push by mass, with the mass behind each side accumulated, moves no centre of
// mass: the chain is a momentum-free position correction.
TEST(ChainMass, PushesInAFreeClusterKeepTheCentreOfMass) {
  World w(world_def(Variant::kModern, VelocityRule::kZero, {0.0, 0.0}));
  std::vector<BodyId> ids;
  std::vector<double> mass;
  // A 4 x 3 block of touching boxes of varied mass, created overlapping a heavy intruder.
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 4; ++c) {
      const double m = 1.0 + static_cast<double>((r * 4 + c) % 5);
      ids.push_back(
          w.create_body(dynamic_box(static_cast<double>(c), static_cast<double>(r), 0.5, m)));
      mass.push_back(m);
    }
  }
  ids.push_back(w.create_body(dynamic_box(-0.7, 1.0, 0.5, 6.0)));
  mass.push_back(6.0);
  const double before = center_of_mass_x(w, ids, mass);
  w.step(kDt);
  EXPECT_NEAR(center_of_mass_x(w, ids, mass), before, 1e-12);
  EXPECT_LT(w.position(ids.back()).x, -0.7);  // the intruder was pushed back out...
  EXPECT_GT(w.position(ids[4]).x, 0.0);       // ...and the block's middle row moved on
}

TEST(ZeroRule, VelocityIntoAContactStopsAndAwayFromItStays) {
  World w(world_def(Variant::kModern, VelocityRule::kZero));
  add_floor(w);
  BodyDef falling = dynamic_box(0.0, 0.52);
  falling.velocity = {1.0, -3.0};
  const BodyId box = w.create_body(falling);
  w.step(kDt);
  EXPECT_FLOAT_EQ(w.velocity(box).y, 0.0);  // stopped by the floor
  EXPECT_FLOAT_EQ(w.velocity(box).x, 1.0);  // no friction: it slides on
  EXPECT_NEAR(w.position(box).y, 0.5, 1e-12);
}

TEST(Restitution, BouncesWithTheGivenFractionOfTheImpactSpeed) {
  World w(world_def(Variant::kModern, VelocityRule::kInelastic));
  add_floor(w);
  BodyDef ball = dynamic_box(0.0, 0.55, 0.5);
  ball.velocity = {0.0, -6.0};
  ball.restitution = 0.5;
  const BodyId id = w.create_body(ball);
  const double impact = -6.0 - 10.0 * kDt;  // gravity acts before the push
  w.step(kDt);
  EXPECT_NEAR(w.velocity(id).y, -0.5 * impact, 1e-12);
  EXPECT_TRUE(w.touching_flags(id) & touching::kBottom);
}

TEST(Restitution, SlowContactsBelowTheThresholdDoNotBounce) {
  World w(world_def(Variant::kModern, VelocityRule::kInelastic));
  add_floor(w);
  BodyDef box = dynamic_box(0.0, 0.5);
  box.restitution = 1.0;
  const BodyId id = w.create_body(box);
  for (int s = 0; s < 120; ++s)
    w.step(kDt);
  EXPECT_FLOAT_EQ(w.velocity(id).y, 0.0);
  EXPECT_NEAR(w.position(id).y, 0.5, 1e-12);
}

TEST(Kinematic, RisingLiftCarriesItsRider) {
  for (const VelocityRule rule : {VelocityRule::kZero, VelocityRule::kInelastic}) {
    World w(world_def(Variant::kModern, rule));
    const BodyId lift = w.create_body(kinematic_box(0.0, 0.0, 2.0, 0.5, {0.0, 1.0}));
    const BodyId rider = w.create_body(dynamic_box(0.0, 1.0));
    for (int s = 0; s < 120; ++s) {
      w.step(kDt);
      ASSERT_NEAR(w.position(rider).y, w.position(lift).y + 1.0, 1e-9) << "step " << s;
    }
    if (rule == VelocityRule::kInelastic) {
      EXPECT_FLOAT_EQ(w.velocity(rider).y, 1.0);
    }
  }
}

TEST(Kinematic, IsNeverPushed) {
  World w(world_def(Variant::kModern, VelocityRule::kInelastic, {0.0, 0.0}));
  const BodyId lift = w.create_body(kinematic_box(0.0, 0.0, 0.5, 0.5, {1.0, 0.0}));
  BodyDef heavy = dynamic_box(1.2, 0.0, 0.5, 1e6);
  heavy.velocity = {-5.0, 0.0};
  const BodyId box = w.create_body(heavy);
  for (int s = 1; s <= 30; ++s) {
    w.step(kDt);
    ASSERT_NEAR(w.position(lift).x, static_cast<double>(s) * kDt, 1e-12);
  }
  EXPECT_FLOAT_EQ(w.velocity(box).x, 1.0);  // the heavy box now moves with the lift
}

}  // namespace
}  // namespace chain::testing
