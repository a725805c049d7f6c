// SPDX-License-Identifier: MIT
// Continuous collision (solver/src/continuous.h): no dynamic body passes through a static or
// kinematic body at any speed up to kMaxSpeed and any dt, and a fast dynamic body does not pass
// through the dynamic bodies in its way.
#include "world_helpers.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace chain::testing {
namespace {

constexpr double kDt = 1.0 / 60.0;

const char* rule_name(VelocityRule r) {
  return r == VelocityRule::kZero ? "zero" : "inelastic";
}

// Issue 3: a 0.5 m crate falling at 25 m/s onto a 0.1 m static slab (top y = 0.05) stops on it at
// (0, 0.3). It used to fall through to y = -17: push-out sends a body through as soon as one
// step's travel passes the slab's centre (about 18 m/s here).
TEST(Continuous, CrateFallingAt25MetresPerSecondStopsOnAThinSlab) {
  for (const VelocityRule rule : {VelocityRule::kZero, VelocityRule::kInelastic}) {
    World w(world_def(Variant::kModern, rule));
    w.create_body(static_box(0.0, 0.0, 2.0, 0.05));
    BodyDef crate = dynamic_box(0.0, 3.0, 0.25);
    crate.velocity = {0.0, -25.0};
    const BodyId id = w.create_body(crate);
    for (int s = 0; s < 120; ++s) {
      w.step(kDt);
      ASSERT_GE(w.position(id).y, 0.3 - 1e-9) << rule_name(rule) << " step " << s;
    }
    EXPECT_EQ(w.position(id).x, 0.0) << rule_name(rule);
    EXPECT_NEAR(w.position(id).y, 0.3, 1e-9) << rule_name(rule);
    EXPECT_NEAR(w.velocity(id).y, 0.0, 1e-12) << rule_name(rule);
  }
}

// A 0.2 m, 1 kg projectile (gravity_scale 0) fired from (-3.5, 2.5) into a stack of five unit
// boxes standing on a floor, a static backstop flush against the stack's far side (left face at
// x = 0.5). At every speed it stops in the stack: against box 2's left face, x = -0.6, never
// beyond it by more than the touch tolerance (overlaps up to it are contact); box 2 stays where it
// is, never pushed into the backstop by more than that.
class Projectile : public ::testing::TestWithParam<double> {};

INSTANTIATE_TEST_SUITE_P(Speeds, Projectile, ::testing::Values(10.0, 50.0, 100.0, 500.0),
                         [](const auto& info) {
                           return std::to_string(static_cast<int>(info.param)) + "MetresPerSecond";
                         });

TEST_P(Projectile, StopsInTheStackAgainstABackstop) {
  for (const VelocityRule rule : {VelocityRule::kZero, VelocityRule::kInelastic}) {
    World w(world_def(Variant::kModern, rule));
    add_floor(w);
    std::vector<BodyId> stack;
    for (int i = 0; i < 5; ++i)
      stack.push_back(w.create_body(dynamic_box(0.0, 0.5 + i)));
    w.create_body(static_box(1.0, 2.5, 0.5, 2.5));
    BodyDef shot = dynamic_box(-3.5, 2.5, 0.1);
    shot.gravity_scale = 0.0;
    shot.velocity = {GetParam(), 0.0};
    const BodyId id = w.create_body(shot);
    const double tol = w.def().touch_tolerance;
    bool arrived = false;
    for (int s = 0; s < 120; ++s) {
      w.step(kDt);
      ASSERT_LE(w.position(id).x, -0.6 + tol) << rule_name(rule) << " step " << s;
      ASSERT_LE(w.position(stack[2]).x + 0.5, 0.5 + tol) << rule_name(rule) << " step " << s;
      arrived = arrived || w.position(id).x >= -0.6 - tol;
    }
    EXPECT_TRUE(arrived) << rule_name(rule);
    EXPECT_NEAR(w.position(id).x, -0.6, tol) << rule_name(rule);
    EXPECT_NEAR(w.velocity(id).x, 0.0, 1e-12) << rule_name(rule);
    for (int i = 0; i < 5; ++i) {
      EXPECT_NEAR(w.position(stack[static_cast<std::size_t>(i)]).x, 0.0, tol)
          << rule_name(rule) << " box " << i;
    }
  }
}

double log_uniform(std::mt19937& rng, double lo, double hi) {
  return std::exp(std::uniform_real_distribution<double>(std::log(lo), std::log(hi))(rng));
}

// Boxes of random sizes at random speeds up to the limit, with random dt, fired at static and
// kinematic slabs of random thickness (kinematic ones moving at random speeds, either way): the
// box's centre never crosses to the slab's other side, and it ends in contact, not inside.
TEST(Continuous, NothingPassesThroughAStaticOrKinematicSlab) {
  std::mt19937 rng(1234);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 400; ++trial) {
    const VelocityRule rule = trial % 2 == 0 ? VelocityRule::kZero : VelocityRule::kInelastic;
    World w(world_def(Variant::kModern, rule, {0.0, 0.0}));
    const int n = trial % 4 < 2 ? 1 : 0;  // the slab's normal axis
    const int t = 1 - n;
    const double dt = log_uniform(rng, 1e-4, 0.5);
    const double speed = log_uniform(rng, 0.1, kMaxSpeed);
    const double half = log_uniform(rng, 0.01, 2.0), thick = log_uniform(rng, 0.001, 1.0);
    const bool kinematic = trial % 3 == 0;
    const double from = unit(rng) < 0.5 ? -1.0 : 1.0;  // which side the box starts on
    // The slab: wide enough that the box meets it, whatever its sideways speed.
    const double slab_speed = kinematic ? (unit(rng) - 0.5) * log_uniform(rng, 0.1, kMaxSpeed) : 0;
    BodyDef slab = static_box(0, 0, 0, 0);
    double* hs = t == 0 ? &slab.half_extents.x : &slab.half_extents.y;
    double* hn = n == 0 ? &slab.half_extents.x : &slab.half_extents.y;
    *hs = 1e7;
    *hn = thick;
    if (kinematic) {
      slab.type = BodyType::kKinematic;
      (n == 0 ? slab.velocity.x : slab.velocity.y) = slab_speed;
    }
    const BodyId slab_id = w.create_body(slab);
    BodyDef box = dynamic_box(0, 0, half);
    box.half_extents = {half, half * (0.5 + unit(rng))};
    const double box_hn = n == 0 ? box.half_extents.x : box.half_extents.y;
    (n == 0 ? box.center.x : box.center.y) = from * (thick + box_hn + unit(rng) * speed * dt);
    (n == 0 ? box.velocity.x : box.velocity.y) = -from * speed;
    (t == 0 ? box.velocity.x : box.velocity.y) = (unit(rng) - 0.5) * speed;
    const BodyId id = w.create_body(box);
    for (int s = 0; s < 4; ++s) {
      w.step(dt);
      const Vec2 p = w.position(id), q = w.position(slab_id);
      const double rel = n == 0 ? p.x - q.x : p.y - q.y;
      ASSERT_GT(from * rel, 0.0) << "trial " << trial << " step " << s << " speed " << speed
                                 << " dt " << dt << " half " << half << " thick " << thick;
      ASSERT_GE(from * rel, thick + box_hn - 1e-9 * std::max(1.0, std::abs(rel)))
          << "trial " << trial << " step " << s;
    }
  }
}

// Fast against dynamic: a box of random size at a random speed up to the limit, fired at a free
// box at rest (random size and mass, no gravity), never ends beyond it: along the line of fire the
// shot's centre stays on its own side, step after step.
TEST(Continuous, FastBoxNeverPassesThroughAFreeBox) {
  std::mt19937 rng(77);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 300; ++trial) {
    const VelocityRule rule = trial % 2 == 0 ? VelocityRule::kZero : VelocityRule::kInelastic;
    World w(world_def(Variant::kModern, rule, {0.0, 0.0}));
    const double dt = log_uniform(rng, 1e-3, 0.1);
    const double speed = log_uniform(rng, 1.0, kMaxSpeed);
    const double target_half = log_uniform(rng, 0.02, 2.0);
    const BodyId target =
        w.create_body(dynamic_box(0.0, 0.0, target_half, log_uniform(rng, 0.01, 100.0)));
    const double half = log_uniform(rng, 0.01, 1.0);
    BodyDef shot = dynamic_box(-(target_half + half) - unit(rng) * speed * dt,
                               (unit(rng) - 0.5) * target_half, half, log_uniform(rng, 0.01, 100));
    shot.velocity = {speed, 0.0};
    const BodyId id = w.create_body(shot);
    for (int s = 0; s < 3; ++s) {
      w.step(dt);
      ASSERT_LT(w.position(id).x, w.position(target).x)
          << "trial " << trial << " step " << s << " speed " << speed << " dt " << dt;
    }
  }
}

// Two fast boxes meeting head-on in one step collide instead of passing through each other.
TEST(Continuous, TwoFastBoxesMeetingHeadOnCollide) {
  for (const VelocityRule rule : {VelocityRule::kZero, VelocityRule::kInelastic}) {
    World w(world_def(Variant::kModern, rule, {0.0, 0.0}));
    BodyDef left = dynamic_box(-2.0, 0.0, 0.1), right = dynamic_box(2.0, 0.1, 0.1);
    left.velocity = {300.0, 0.0};
    right.velocity = {-300.0, 0.0};
    const BodyId a = w.create_body(left), b = w.create_body(right);
    for (int s = 0; s < 10; ++s) {
      w.step(kDt);
      ASSERT_LT(w.position(a).x, w.position(b).x) << rule_name(rule) << " step " << s;
    }
    EXPECT_EQ(w.last_step_stats().budget_hits, 0u);
    if (rule == VelocityRule::kInelastic) {  // equal masses, head-on: they stop together
      EXPECT_NEAR(w.velocity(a).x, 0.0, 1e-9);
      EXPECT_NEAR(w.velocity(b).x, 0.0, 1e-9);
    }
  }
}

// A driven pusher and a row of touching boxes, no gravity: every step the pusher is set to v and
// moves v dt into the row, and push-out shares that overlap out along the row. The row ends each
// step touching, so where it goes follows from momentum alone. Zero rule: the pushed boxes gain
// no velocity and the position split keeps the mass-weighted centre, so the row advances
// pusher v dt / (pusher + row) a step. Inelastic rule: the group leaves at its mass-weighted mean
// velocity, u_k = (pusher v + row u_{k-1}) / (pusher + row), and advances u_k dt.
double analytic_push(VelocityRule rule, double v, double dt, double pusher, double row, double& u) {
  const double total = pusher + row;
  if (rule == VelocityRule::kZero) return pusher * v * dt / total;
  u = (pusher * v + row * u) / total;
  return u * dt;
}

// Issue 1: a pusher driven at 27 m/s moves 0.45 m a step, more than half its half extent, so it
// counts as fast; continuous collision used to stop it a quarter box into the first box, and the
// row moved 5 m/s instead of 27 / 3 = 9 m/s (zero rule, two boxes of the pusher's mass).
TEST(Continuous, FastDrivenPusherPushesTwoBoxesAtAThirdOfItsSpeed) {
  World w(world_def(Variant::kModern, VelocityRule::kZero, {0.0, 0.0}));
  const BodyId pusher = w.create_body(dynamic_box(0.0, 0.0));
  const BodyId b1 = w.create_body(dynamic_box(1.0, 0.0)), b2 = w.create_body(dynamic_box(2.0, 0.0));
  w.set_drive(pusher, {27.0, 0.0});
  for (int s = 1; s <= 60; ++s) {
    w.step(kDt);
    ASSERT_NEAR(w.position(pusher).x, s * 9.0 * kDt, 1e-9) << "step " << s;
    ASSERT_NEAR(w.position(b1).x, 1.0 + s * 9.0 * kDt, 1e-9) << "step " << s;
    ASSERT_NEAR(w.position(b2).x, 2.0 + s * 9.0 * kDt, 1e-9) << "step " << s;
  }
  EXPECT_NEAR(w.position(b2).x, 11.0, 1e-9);
}

// The kind: a driven pusher at any speed from walking pace to hundreds of m/s, of the row's box
// mass or heavier, into rows of 1 to 8 boxes, both velocity rules, pushes the row the analytic
// distance every step (within the touch tolerance per contact). Boxes are sized so that one step's
// travel stays within what push-out undoes (up to 5/6 of the way to the first box's centre): the
// sweep must then change nothing.
TEST(Continuous, DrivenPusherPushesTheAnalyticDistanceAtAnySpeed) {
  for (const VelocityRule rule : {VelocityRule::kZero, VelocityRule::kInelastic}) {
    for (const double v : {0.5, 3.0, 14.0, 27.0, 45.0, 100.0, 300.0, 700.0}) {
      for (const int n : {1, 2, 3, 5, 8}) {
        for (const double pusher_mass : {1.0, 4.0}) {
          const double half = std::max(0.5, 0.6 * v * kDt);  // travel up to 5/6 of 2 half
          World w(world_def(Variant::kModern, rule, {0.0, 0.0}));
          const BodyId pusher = w.create_body(dynamic_box(0.0, 0.0, half, pusher_mass));
          std::vector<BodyId> row;
          for (int i = 1; i <= n; ++i)
            row.push_back(w.create_body(dynamic_box(2.0 * half * i, 0.0, half)));
          w.set_drive(pusher, {v, 0.0});
          double u = 0.0, travelled = 0.0;
          for (int s = 1; s <= 20; ++s) {
            const double before = w.position(row.back()).x;
            w.step(kDt);
            const double expected = analytic_push(rule, v, kDt, pusher_mass, n, u);
            travelled += expected;
            const double moved = w.position(row.back()).x - before;
            // Overlaps up to the touch tolerance are contact: each of the n + 1 contacts may keep
            // one, step after step, and rounding grows with the distance travelled.
            const double step_tol = (n + 1) * w.def().touch_tolerance + 1e-12 * travelled;
            ASSERT_NEAR(moved, expected, step_tol) << rule_name(rule) << " v " << v << " n " << n
                                                   << " pusher " << pusher_mass << " step " << s;
            for (int i = 0; i < n; ++i) {
              ASSERT_NEAR(w.position(row[static_cast<std::size_t>(i)]).x,
                          2.0 * half * (i + 1) + travelled, s * step_tol)
                  << rule_name(rule) << " v " << v << " n " << n << " box " << i << " step " << s;
            }
          }
        }
      }
    }
  }
}

// A fast box sliding along a floor is swept (it moves several times its size a step) but meets
// nothing: it keeps its speed and slides exactly as a slow one, and is reported fast, not cut.
TEST(Continuous, FastBoxSlidingOnAFloorIsNotSlowed) {
  World w(world_def(Variant::kModern, VelocityRule::kInelastic));
  add_floor(w, 1000.0);
  BodyDef box = dynamic_box(0.0, 0.1, 0.1);
  box.velocity = {120.0, 0.0};
  const BodyId id = w.create_body(box);
  for (int s = 1; s <= 60; ++s) {
    w.step(kDt);
    ASSERT_NEAR(w.position(id).x, s * (120.0 * kDt), 1e-9) << "step " << s;
    ASSERT_NEAR(w.position(id).y, 0.1, 1e-12) << "step " << s;
    ASSERT_EQ(w.last_step_stats().fast_bodies, 1u);
  }
  EXPECT_EQ(w.velocity(id).x, 120.0);
  EXPECT_TRUE(w.touching_flags(id) & touching::kBottom);
}

// A fast kinematic platform rising at 300 m/s into a box resting above it carries the box up
// instead of passing through it.
TEST(Continuous, FastKinematicPlatformCarriesWhatItMeets) {
  for (const VelocityRule rule : {VelocityRule::kZero, VelocityRule::kInelastic}) {
    World w(world_def(Variant::kModern, rule));
    const BodyId lift = w.create_body(kinematic_box(0.0, -10.0, 2.0, 0.05, {0.0, 300.0}));
    w.create_body(static_box(0.0, 1.0, 0.3, 0.3));  // something the box rests on, aside the path
    const BodyId box = w.create_body(dynamic_box(0.0, 1.55, 0.25));
    for (int s = 0; s < 10; ++s) {
      w.step(kDt);
      const double lift_top = w.position(lift).y + 0.05;
      if (lift_top > 1.3) {
        ASSERT_NEAR(w.position(box).y, lift_top + 0.25, 1e-9) << rule_name(rule) << " " << s;
      }
    }
  }
}

// A stack of three boxes on a platform rising several box heights a step stays a stack: each box
// rests on the one below, none is pushed aside. The third box overhangs the platform, resting
// only on the second: it is carried on top of it all the same.
TEST(Continuous, StackOnAFastPlatformStaysStacked) {
  for (const VelocityRule rule : {VelocityRule::kZero, VelocityRule::kInelastic}) {
    for (const double speed : {100.0, 250.0, 1000.0}) {
      World w(world_def(Variant::kModern, rule));
      w.create_body(static_box(0.0, -1.0, 10.0, 1.0));
      const BodyId lift = w.create_body(kinematic_box(0.0, -3.0, 1.0, 0.5, {0.0, speed}));
      const double x[3] = {0.0, 0.8, 1.7};  // the third box lies beyond the platform's edge
      std::vector<BodyId> stack;
      for (int i = 0; i < 3; ++i)
        stack.push_back(w.create_body(dynamic_box(x[i], 0.5 + i)));
      for (int s = 0; s < 30; ++s)
        w.step(kDt);
      const double top = w.position(lift).y + 0.5;
      for (int i = 0; i < 3; ++i) {
        const BodyId id = stack[static_cast<std::size_t>(i)];
        EXPECT_EQ(w.position(id).x, x[i]) << rule_name(rule) << " " << speed << " box " << i;
        EXPECT_NEAR(w.position(id).y, top + 0.5 + i, 1e-9)
            << rule_name(rule) << " " << speed << " box " << i;
      }
    }
  }
}

// A platform rising at 200 m/s lifts a box into a static ceiling that the platform itself passes
// through: the box cannot give way, so it is reported crushed, naming the platform and the
// ceiling, and it never goes into the ceiling.
TEST(Continuous, FastLiftSqueezingABoxIntoACeilingReportsTheCrush) {
  for (const VelocityRule rule : {VelocityRule::kZero, VelocityRule::kInelastic}) {
    World w(world_def(Variant::kModern, rule));
    const BodyId ceiling = w.create_body(static_box(0.0, 10.0, 5.0, 0.5));
    const BodyId lift = w.create_body(kinematic_box(0.0, -20.0, 2.0, 0.5, {0.0, 200.0}));
    const BodyId box = w.create_body(dynamic_box(0.0, 5.0));
    int crushes = 0;
    for (int s = 0; s < 20; ++s) {
      w.step(kDt);
      ASSERT_LE(w.position(box).y + 0.5, 9.5 + 1e-9) << rule_name(rule) << " step " << s;
      for (const CrushEvent& e : w.crush_events()) {
        EXPECT_EQ(e.body, box);
        EXPECT_EQ(e.anchor, lift);
        EXPECT_EQ(e.blocker, ceiling);
        EXPECT_EQ(e.axis, Axis::kY);
        ++crushes;
      }
    }
    EXPECT_GE(crushes, 1) << rule_name(rule);
  }
}

}  // namespace
}  // namespace chain::testing
