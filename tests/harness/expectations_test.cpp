// SPDX-License-Identifier: MIT
// Expectations: every kind judged on the states it names, its worst state traced to a body and a
// step, with figures worked out by hand.
#include "run/runner.h"
#include "scenes/scene_library.h"

#include <gtest/gtest.h>

#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>

namespace chainbench {
namespace {

using Kind = Expectation::Kind;

// Top-down, frictionless: a box sliding at 1 m/s along x, and one at rest beside its path.
Scene slider() {
  Scene s;
  s.name = "slider";
  s.gravity = {0, 0};
  s.steps = 60;
  s.bodies.push_back({"slider", BodyKind::kDynamic, {0, 0}, {0.5, 0.5}, {1, 0}, 1, 1, {}, {}});
  s.bodies.push_back({"still", BodyKind::kDynamic, {0, 3}, {0.5, 0.5}, {}, 1, 1, {}, {}});
  return s;
}

ExpectResult check(const Scene& s, const char* engine = "chain",
                   MetricSelection metrics = MetricSelection::none()) {
  RunOptions options;
  options.metrics = metrics;
  const EngineRun run = run_engine(s, parse_engine_spec(engine), options);
  EXPECT_TRUE(run.expect.has_value());
  return run.expect.value_or(ExpectResult{});
}

// The slider travels 1 m in 60 steps: its centre ends at (1, 0).
TEST(Expectations, CenterAndMovedAreJudgedOnTheFinalState) {
  Scene s = slider();
  s.expect = {build::expect_center(0, {1.0, 0.0}, 1e-9), build::expect_center(0, {1.1, 0.0}, 0.05),
              build::expect_moved(build::kEvery, {0.0, 0.0}, 0.01)};
  // The runner checks expectations even when no metric is asked for: they are the truth.
  const ExpectResult r = check(s);
  ASSERT_EQ(r.entries.size(), 3u);
  EXPECT_TRUE(r.entries[0].pass);
  EXPECT_NEAR(r.entries[0].value, 0.0, 1e-12);
  EXPECT_EQ(r.entries[0].state, 60);
  EXPECT_FALSE(r.entries[1].pass);
  EXPECT_NEAR(r.entries[1].error, 0.1, 1e-12);
  // Of every dynamic body, the slider moved: 1 m from where it started.
  EXPECT_FALSE(r.entries[2].pass);
  EXPECT_EQ(*r.entries[2].body, 0u);
  EXPECT_NEAR(r.entries[2].value, 1.0, 1e-12);
  EXPECT_NEAR(r.entries[2].position.x, 1.0, 1e-12);
  EXPECT_EQ(r.entries[2].bodies, 2u);
  EXPECT_NEAR(r.entries[2].rms, std::sqrt(0.5), 1e-12);  // one body 1 m off, the other 0
  EXPECT_FALSE(r.pass);
  EXPECT_NEAR(r.max_error, 1.0, 1e-12);
}

// A window checks every state in it and keeps the worst: the slider passes x = 0.5 after 30
// steps, so "x <= 0.5 over [0, 40]" fails first at state 31 and is worst at state 40
// (0.1667 m beyond).
TEST(Expectations, AWindowIsCheckedAtEveryStateAndKeepsItsWorst) {
  Scene s = slider();
  Expectation bound = build::expect_bounds(0, std::nullopt, std::nullopt, 0.5, std::nullopt);
  bound.from_step = 0;
  bound.to_step = 40;
  Expectation early = bound;
  early.to_step = 30;  // ends before it goes past
  s.expect = {bound, early};
  const ExpectResult r = check(s);
  EXPECT_FALSE(r.entries[0].pass);
  EXPECT_EQ(r.entries[0].state, 40);
  EXPECT_NEAR(r.entries[0].error, 40.0 / 60.0 - 0.5, 1e-9);
  EXPECT_TRUE(r.entries[1].pass);
  EXPECT_EQ(r.entries[1].state, 30);  // the state nearest to failing
}

// Rest is speed measured from positions, so a velocity rule that zeroes velocities cannot hide
// a moving body; at the start (state 0) it is the initial velocity.
TEST(Expectations, AtRestMeasuresSpeedFromDisplacement) {
  Scene s = slider();
  Expectation moving;
  moving.kind = Kind::kAtRest;
  moving.body = Expectation::kEveryDynamic;
  moving.speed = 0.5;
  Expectation still = moving;
  still.body = 1;
  still.speed = 1e-9;
  still.from_step = 0;
  s.expect = {moving, still};
  const ExpectResult r = check(s);
  EXPECT_FALSE(r.entries[0].pass);
  EXPECT_EQ(*r.entries[0].body, 0u);
  EXPECT_NEAR(r.entries[0].value, 1.0, 1e-9);
  EXPECT_NEAR(r.entries[0].error, 0.5, 1e-9);
  EXPECT_TRUE(r.entries[1].pass);
}

// Two boxes created 0.2 m into each other, top-down: the chain solver separates them in its first
// step, so "no overlap from step 1" holds and "no overlap from step 0" fails at the start, naming
// both.
TEST(Expectations, NoOverlapNamesTheDeepestPair) {
  Scene s = slider();
  s.bodies[0].velocity = {};
  s.bodies[1].center = {0.8, 0.0};
  Expectation from_one = build::expect_no_overlap(1e-6, 1);
  Expectation from_zero = build::expect_no_overlap(1e-6, 0);
  s.expect = {from_one, from_zero};
  const ExpectResult r = check(s);
  EXPECT_TRUE(r.entries[0].pass);
  EXPECT_FALSE(r.entries[1].pass);
  EXPECT_EQ(r.entries[1].state, 0);
  EXPECT_NEAR(r.entries[1].value, 0.2, 1e-12);
  EXPECT_EQ(*r.entries[1].body, 0u);
  EXPECT_EQ(*r.entries[1].other, 1u);
  // With the metrics on, the same answers come from the recorder's own scan.
  const ExpectResult with_metrics = check(s, "chain", MetricSelection{});
  EXPECT_TRUE(with_metrics.entries[0].pass);
  EXPECT_NEAR(with_metrics.entries[1].value, 0.2, 1e-12);
}

// A run stopped before an entry's window never checked it: that is not a pass.
TEST(Expectations, AnEntryNeverCheckedFails) {
  Scene s = slider();
  s.expect = {build::expect_center(0, {1.0, 0.0}, 0.01)};
  std::atomic<bool> stop{true};
  RunOptions options;
  options.stop = &stop;
  const EngineRun run = run_engine(s, parse_engine_spec("chain"), options);
  ASSERT_TRUE(run.expect.has_value());
  EXPECT_FALSE(run.expect->entries[0].pass);
  EXPECT_EQ(run.expect->entries[0].state, -1);
}

// A built-in scene built with an offset keeps its right answer: bounds move with it.
TEST(Expectations, OffsetMovesBoundsAndCentres) {
  const Scene plain = make_scene("projectile", {"speed=10"});
  const Scene moved = make_scene("projectile", {"speed=10", "offset=1000"});
  ASSERT_EQ(plain.expect.size(), moved.expect.size());
  EXPECT_NEAR(*moved.expect[0].max_x - *plain.expect[0].max_x, 1000.0, 1e-9);
  EXPECT_NEAR(moved.expect[1].center.y - plain.expect[1].center.y, 1000.0, 1e-9);
  RunOptions options;
  options.metrics = MetricSelection::none();
  EXPECT_TRUE(run_engine(moved, parse_engine_spec("chain"), options).expect->pass);
}

// needs_state() and needs_depth(), worked out once per run, say for every state what the windows
// do: a state in some entry's window, or just before an at_rest window (its first speed), and a
// state in a no_overlap window.
TEST(Expectations, StatesNeededAreThoseOfTheWindows) {
  Scene s = slider();
  s.steps = 40;
  std::uint64_t seed = 3;
  auto next = [&](int n) {
    seed = seed * 6364136223846793005u + 1442695040888963407u;
    return static_cast<int>((seed >> 33) % static_cast<std::uint64_t>(n));
  };
  for (int round = 0; round < 50; ++round) {
    s.expect.clear();
    for (int e = 0, n = next(4); e < n; ++e) {
      Expectation x;
      x.kind = std::array{Kind::kCenter, Kind::kBounds, Kind::kAtRest, Kind::kNoOverlap}[next(4)];
      x.body = 0;
      if (next(3) != 0) {
        const int a = next(s.steps + 1), b = next(s.steps + 1);
        x.from_step = std::min(a, b);
        if (next(2) != 0) x.to_step = std::max(a, b);
      }
      s.expect.push_back(x);
    }
    const ExpectationCheck check(s);
    for (int k = -1; k <= s.steps + 1; ++k) {
      bool state = false, depth = false;
      for (const Expectation& e : s.expect) {
        const int first = e.first_state(s.steps), last = e.last_state(s.steps);
        const bool in = k >= first && k <= last;
        state = state || in || (e.kind == Kind::kAtRest && k + 1 >= first && k + 1 <= last);
        depth = depth || (e.kind == Kind::kNoOverlap && in);
      }
      EXPECT_EQ(check.needs_state(k), state) << "round " << round << " state " << k;
      EXPECT_EQ(check.needs_depth(k), depth) << "round " << round << " state " << k;
    }
  }
}

}  // namespace
}  // namespace chainbench
