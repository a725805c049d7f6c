// SPDX-License-Identifier: MIT
// World::set_profiling times each stage of a step (StepProfile) and changes no result: a world
// profiled and one not step to the same bits, in both variants and with every stage at work.
#include "world_helpers.h"

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <iterator>
#include <set>
#include <string>
#include <vector>

namespace chain::testing {
namespace {

constexpr double kDt = 1.0 / 60.0;

// A stack, rough crates on a moving platform (friction), a fast box fired at a wall (continuous
// collision), two boxes created overlapping (pushes in the first step) and a driven pusher against
// a row.
std::vector<BodyId> build(World& w) {
  std::vector<BodyId> ids;
  ids.push_back(add_floor(w));
  for (int i = 0; i < 5; ++i)
    ids.push_back(w.create_body(dynamic_box(-10.0, 0.5 + i)));
  BodyDef platform = kinematic_box(0.0, 0.25, 2.0, 0.25, {1.0, 0.0});
  platform.friction = 1.0;
  ids.push_back(w.create_body(platform));
  for (int i = 0; i < 2; ++i) {
    BodyDef crate = dynamic_box(0.0, 1.0 + i, 0.5);
    crate.friction = 0.8;
    ids.push_back(w.create_body(crate));
  }
  ids.push_back(w.create_body(static_box(20.0, 2.0, 0.5, 2.0)));
  BodyDef shot = dynamic_box(10.0, 1.0, 0.1);
  shot.velocity = {300.0, 0.0};
  ids.push_back(w.create_body(shot));
  ids.push_back(w.create_body(dynamic_box(-20.0, 0.5)));
  ids.push_back(w.create_body(dynamic_box(-19.4, 0.5)));
  for (int i = 0; i < 4; ++i)
    ids.push_back(w.create_body(dynamic_box(-30.0 + i, 0.5)));
  const BodyId pusher = w.create_body(dynamic_box(-31.5, 0.5, 0.5, 3.0));
  w.set_drive(pusher, {1.5, 0.0}, DriveAxes::kX);
  ids.push_back(pusher);
  return ids;
}

bool same_bits(Vec2 a, Vec2 b) {
  return std::bit_cast<std::uint64_t>(a.x) == std::bit_cast<std::uint64_t>(b.x) &&
         std::bit_cast<std::uint64_t>(a.y) == std::bit_cast<std::uint64_t>(b.y);
}

double staged_sum(const StepProfile& p) {
  double sum = 0.0;
  for (const StepStage& s : kStepStages)
    sum += p.*s.ms;
  return sum;
}

class StepProfileTest : public ::testing::TestWithParam<Variant> {};

INSTANTIATE_TEST_SUITE_P(Variants, StepProfileTest,
                         ::testing::Values(Variant::kModern, Variant::kSeed2014),
                         [](const auto& info) { return std::string(variant_name(info.param)); });

TEST_P(StepProfileTest, ProfilingChangesNoResultAndEveryStageIsTimed) {
  const WorldDef def = world_def(GetParam(), VelocityRule::kInelastic);
  World profiled(def), plain(def);
  const std::vector<BodyId> a = build(profiled), b = build(plain);
  profiled.set_profiling(true);
  for (int s = 0; s < 90; ++s) {
    profiled.step(kDt);
    plain.step(kDt);
    for (std::size_t i = 0; i < a.size(); ++i) {
      ASSERT_TRUE(same_bits(profiled.position(a[i]), plain.position(b[i])))
          << "body " << i << " at step " << s + 1;
      ASSERT_TRUE(same_bits(profiled.velocity(a[i]), plain.velocity(b[i])))
          << "body " << i << " at step " << s + 1;
    }
    const StepProfile& p = profiled.last_step_profile();
    for (const StepStage& st : kStepStages)
      ASSERT_GE(p.*st.ms, 0.0) << st.name;
    // The stages are laps of one clock from the step's start, so together they fit in it.
    ASSERT_GT(p.total, 0.0);
    ASSERT_LE(staged_sum(p), p.total * (1.0 + 1e-12));
    // A world not profiled reports nothing.
    const StepProfile& q = plain.last_step_profile();
    ASSERT_EQ(q.total, 0.0);
    ASSERT_EQ(staged_sum(q), 0.0);
  }
}

TEST(StepProfile, TurnedOffItReportsZerosAgain) {
  World w;
  build(w);
  w.set_profiling(true);
  w.step(kDt);
  EXPECT_GT(w.last_step_profile().total, 0.0);
  w.set_profiling(false);
  w.step(kDt);
  EXPECT_EQ(w.last_step_profile().total, 0.0);
  EXPECT_EQ(staged_sum(w.last_step_profile()), 0.0);
}

// The table names every stage once, in step order, and leaves none of StepProfile out.
TEST(StepProfile, TheStageTableCoversEveryFieldButTheTotal) {
  std::set<std::string> names;
  for (const StepStage& s : kStepStages)
    names.insert(s.name);
  EXPECT_EQ(names.size(), std::size(kStepStages));
  for (std::size_t i = 0; i < std::size(kStepStages); ++i) {
    EXPECT_FALSE(kStepStages[i].ms == &StepProfile::total) << kStepStages[i].name;
    for (std::size_t j = i + 1; j < std::size(kStepStages); ++j)
      EXPECT_FALSE(kStepStages[i].ms == kStepStages[j].ms) << kStepStages[i].name;
  }
  EXPECT_EQ(sizeof(StepProfile), (std::size(kStepStages) + 1) * sizeof(double));
  const std::vector<std::string> order = {"prepare", "integrate", "continuous", "contacts",
                                          "chains",  "velocity",  "friction",   "layout"};
  for (std::size_t i = 0; i < order.size(); ++i)
    EXPECT_EQ(kStepStages[i].name, order[i]);
}

}  // namespace
}  // namespace chain::testing
