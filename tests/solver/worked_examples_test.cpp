// SPDX-License-Identifier: MIT
// The worked examples of the 2014 design (docs/algorithm-2014.md §3; conversions §1), converted
// from px/frame to metres and seconds, checked in both variants unless the example is modern-only.
#include "world_helpers.h"

#include <gtest/gtest.h>

#include <vector>

namespace chain::testing {
namespace {

constexpr double kDt = 1.0 / 60.0;

class BothVariants : public ::testing::TestWithParam<Variant> {};

INSTANTIATE_TEST_SUITE_P(Solver, BothVariants,
                         ::testing::Values(Variant::kModern, Variant::kSeed2014),
                         [](const auto& info) { return variant_name(info.param); });

// docs/algorithm-2014.md §3.1: a player at +4 pushing two touching boxes of equal mass moves the
// three together, each by 4/3. With the zero rule the push repeats every step, so each body
// advances v*dt/3.
TEST_P(BothVariants, DrivenPusherMovesTwoTouchingBoxesAThirdOfItsStepEach) {
  World w(world_def(GetParam(), VelocityRule::kZero, {0.0, 0.0}));
  const double v = 2.0;
  const BodyId pusher = w.create_body(dynamic_box(0.0, 0.0));
  const BodyId box1 = w.create_body(dynamic_box(1.0, 0.0));
  const BodyId box2 = w.create_body(dynamic_box(2.0, 0.0));
  w.set_drive(pusher, {v, 0.0});
  for (int step = 1; step <= 60; ++step) {
    w.step(kDt);
    const double advance = static_cast<double>(step) * v * kDt / 3.0;
    ASSERT_NEAR(w.position(pusher).x, 0.0 + advance, 1e-9) << "step " << step;
    ASSERT_NEAR(w.position(box1).x, 1.0 + advance, 1e-9) << "step " << step;
    ASSERT_NEAR(w.position(box2).x, 2.0 + advance, 1e-9) << "step " << step;
    ASSERT_FLOAT_EQ(w.position(box2).y, 0.0);
  }
}

// docs/algorithm-2014.md §3.2: against a wall, the player goes back to where it started and the
// box stays.
TEST_P(BothVariants, RowAgainstStaticWallDoesNotMove) {
  for (const VelocityRule rule : {VelocityRule::kZero, VelocityRule::kInelastic}) {
    World w(world_def(GetParam(), rule, {0.0, 0.0}));
    std::vector<BodyId> ids = {
        w.create_body(dynamic_box(0.0, 0.0)), w.create_body(dynamic_box(1.0, 0.0)),
        w.create_body(dynamic_box(2.0, 0.0)), w.create_body(static_box(3.0, 0.0, 0.5, 2.0))};
    w.set_drive(ids[0], {2.0, 0.0});
    for (int step = 0; step < 120; ++step) {
      w.step(kDt);
      for (int i = 0; i < 3; ++i) {
        ASSERT_NEAR(w.position(ids[i]).x, static_cast<double>(i), 1e-9) << "body " << i;
      }
      ASSERT_LE(max_penetration(w, ids, {{0.5, 0.5}, {0.5, 0.5}, {0.5, 0.5}, {0.5, 2.0}}),
                w.def().touch_tolerance);
    }
    if (rule == VelocityRule::kInelastic) {
      EXPECT_FLOAT_EQ(w.velocity(ids[1]).x, 0.0);  // the row stopped with the wall
      EXPECT_FLOAT_EQ(w.velocity(ids[2]).x, 0.0);
    }
  }
}

// docs/algorithm-2014.md §3.3, the chaining axis: a box resting on the floor and pushed sideways
// keeps its resting contact out of the push. Were the floor contact chained sideways, the box would
// act as a wall and the pusher would take the whole push (mass ignored); instead the push splits by
// mass every step.
TEST_P(BothVariants, RestingContactIsNotResolvedSideways) {
  World w(world_def(GetParam(), VelocityRule::kZero));
  add_floor(w);
  const BodyId pusher = w.create_body(dynamic_box(0.0, 0.5));
  const BodyId box = w.create_body(dynamic_box(1.0, 0.5));
  const double v = 1.0;
  w.set_drive(pusher, {v, 0.0});
  for (int step = 1; step <= 60; ++step) {
    w.step(kDt);
    const double advance = static_cast<double>(step) * v * kDt / 2.0;
    ASSERT_NEAR(w.position(box).x, 1.0 + advance, 1e-9) << "step " << step;
    ASSERT_NEAR(w.position(pusher).x, advance, 1e-9) << "step " << step;
    ASSERT_NEAR(w.position(box).y, 0.5, 1e-9);  // still resting on the floor
    ASSERT_NEAR(w.position(pusher).y, 0.5, 1e-9);
  }
  EXPECT_TRUE(w.touching_flags(box) & touching::kBottom);
  EXPECT_TRUE(w.touching_flags(box) & touching::kLeft);
  EXPECT_TRUE(w.touching_flags(pusher) & touching::kRight);
}

// A lift descending onto a box on the floor: every step terminates; modern reports the crush
// and names both immovable bodies.
TEST_P(BothVariants, BoxBetweenFloorAndDescendingLiftTerminates) {
  World w(world_def(GetParam(), VelocityRule::kInelastic));
  const BodyId floor = add_floor(w);
  const BodyId box = w.create_body(dynamic_box(0.0, 0.5));
  const BodyId lift = w.create_body(kinematic_box(0.0, 2.0, 1.5, 0.5, {0.0, -0.5}));
  int crush_steps = 0;
  for (int step = 0; step < 170; ++step) {
    w.step(kDt);
    const StepStats& s = w.last_step_stats();
    ASSERT_EQ(s.budget_hits, 0u) << "step " << step;
    ASSERT_TRUE(std::isfinite(w.position(box).x) && std::isfinite(w.position(box).y));
    if (!w.crush_events().empty()) ++crush_steps;
  }
  // The lift's bottom meets the box's top after 1 s (step 60) and is still above the floor at
  // step 170: a squeeze on every one of those steps.
  EXPECT_GT(crush_steps, 100);
  if (GetParam() == Variant::kModern) {
    ASSERT_EQ(w.crush_events().size(), 1u);
    const CrushEvent e = w.crush_events()[0];
    EXPECT_EQ(e.body, box);
    EXPECT_EQ(e.axis, Axis::kY);
    EXPECT_TRUE((e.anchor == floor && e.blocker == lift) ||
                (e.anchor == lift && e.blocker == floor));
    // Centred between the two: it overlaps both by the same depth.
    const double box_y = w.position(box).y;
    const double lift_bottom = w.position(lift).y - 0.5;
    EXPECT_NEAR(box_y - 0.5 - 0.0, lift_bottom - (box_y + 0.5), 1e-9);
  }
}

// A stack of 10 under gravity rests: the push-out leaves under 1 mm of overlap and the stack
// drifts under 1 mm in 600 steps, at equal masses and at 100:1 in either direction.
struct StackCase {
  const char* name;
  double bottom_mass, top_mass;
  VelocityRule rule;
};
void PrintTo(const StackCase& c, std::ostream* os) {
  *os << c.name;
}

class RestingStack : public ::testing::TestWithParam<StackCase> {};

INSTANTIATE_TEST_SUITE_P(
    Modern, RestingStack,
    ::testing::Values(StackCase{"EqualInelastic", 1.0, 1.0, VelocityRule::kInelastic},
                      StackCase{"EqualZero", 1.0, 1.0, VelocityRule::kZero},
                      StackCase{"HeavyTopInelastic", 1.0, 100.0, VelocityRule::kInelastic},
                      StackCase{"HeavyTopZero", 1.0, 100.0, VelocityRule::kZero},
                      StackCase{"HeavyBottomInelastic", 100.0, 1.0, VelocityRule::kInelastic}),
    [](const auto& info) { return std::string(info.param.name); });

TEST_P(RestingStack, TenBoxesRestWithinAMillimetreFor600Steps) {
  const StackCase c = GetParam();
  World w(world_def(Variant::kModern, c.rule));
  std::vector<BodyId> ids = {add_floor(w)};
  std::vector<Vec2> half = {{50.0, 1.0}};
  for (int i = 0; i < 10; ++i) {
    const double mass = i == 0 ? c.bottom_mass : (i == 9 ? c.top_mass : 1.0);
    ids.push_back(w.create_body(dynamic_box(0.0, 0.5 + static_cast<double>(i), 0.5, mass)));
    half.push_back({0.5, 0.5});
  }
  for (int step = 0; step < 600; ++step) {
    w.step(kDt);
    ASSERT_LT(max_penetration(w, ids, half), 1e-3) << "step " << step;
  }
  for (int i = 0; i < 10; ++i) {
    const Vec2 p = w.position(ids[static_cast<std::size_t>(i) + 1]);
    EXPECT_NEAR(p.x, 0.0, 1e-3) << "box " << i;
    EXPECT_NEAR(p.y, 0.5 + static_cast<double>(i), 1e-3) << "box " << i;
  }
}

}  // namespace
}  // namespace chain::testing
