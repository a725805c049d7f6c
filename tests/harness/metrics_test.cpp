// SPDX-License-Identifier: MIT
// Each metric on cases small enough to compute by hand.
#include "judge/metrics.h"
#include "index/pair_scan.h"
#include "judge/tunnelling.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <set>

namespace chainbench {
namespace {

Scene two_boxes(Vec2d a, Vec2d b, BodyKind kind_b = BodyKind::kDynamic) {
  Scene s;
  s.gravity = {0.0, 0.0};
  s.dt = 0.1;
  s.steps = 10;
  s.bodies.push_back({"a", BodyKind::kDynamic, a, {0.5, 0.5}, {}, 1.0, 1.0, {}, {}});
  s.bodies.push_back({"b", kind_b, b, {0.5, 0.5}, {}, 1.0, 1.0, {}, {}});
  return s;
}

BodyState state(std::vector<Vec2d> pos, std::vector<Vec2d> vel = {}) {
  BodyState s(pos.size());
  s.position = std::move(pos);
  if (!vel.empty()) s.velocity = std::move(vel);
  return s;
}

TEST(Metrics, EnergyFreeDisplacementIsTheMoveVelocityDoesNotExplain) {
  const Scene s = two_boxes({0, 0}, {5, 0});
  MetricsRecorder m(s, MetricSelection{true, false, false});
  // a moves 0.3 m in x while its velocity after the step explains 0.1 * 2 = 0.2: 0.1 was a push.
  // b moves 0.4 m in y with no velocity at all: 0.4 of push.
  m.observe(state({{0, 0}, {5, 0}}), state({{0.3, 0}, {5, 0.4}}, {{2, 0}, {0, 0}}), 1, true);
  const BodyState end = state({{0.5, 0}, {5, 0.4}}, {{2, 0}, {0, 0}});
  m.observe(state({{0.3, 0}, {5, 0.4}}, {{2, 0}, {0, 0}}), end, 2, false);
  const Metrics r = m.result(end);
  EXPECT_NEAR(*r.efd_total, 0.1 + 0.4, 1e-12);
  EXPECT_NEAR(*r.efd_max_step, 0.4, 1e-12);
  EXPECT_NEAR(*r.efd_per_body_step, 0.5 / 4.0, 1e-12);  // 2 bodies x 2 steps
  EXPECT_FALSE(r.max_penetration.has_value());          // not asked for
  EXPECT_FALSE(r.finite.has_value());
}

// A body at x = 0.2 coasting at 3 m/s with dt = 0.1 ends at 0.2 + 0.3, and in doubles that minus
// 0.2 minus 0.3 is -5.6e-17 m: rounding, no push, so it reads 0, as docs/reading-the-tables.md
// §3 says of figures below the arithmetic's resolution. A push of 1e-9 m is real and counts.
TEST(Metrics, EnergyFreeDisplacementBelowRoundingIsZero) {
  const Scene s = two_boxes({0.2, 0}, {5, 0});
  MetricsRecorder m(s, MetricSelection{true, false, false});
  const BodyState start = state({{0.2, 0}, {5, 0}}, {{3, 0}, {0, 0}});
  const BodyState coast = state({{0.2 + 0.1 * 3.0, 0}, {5, 0}}, {{3, 0}, {0, 0}});
  ASSERT_NE(coast.position[0].x - 0.2 - 0.1 * 3.0, 0.0);  // there is rounding to ignore
  m.observe(start, coast, 1, true);
  EXPECT_EQ(*m.result(coast).efd_total, 0.0);
  const BodyState pushed = state({{coast.position[0].x + 0.3 + 1e-9, 0}, {5, 0}}, {{3, 0}, {0, 0}});
  m.observe(coast, pushed, 2, true);
  EXPECT_NEAR(*m.result(pushed).efd_total, 1e-9, 1e-15);
}

double deepest(const Scene& s, const BodyState& st) {
  return MetricsRecorder::deepest_overlap(s, st, 0).depth;
}

TEST(Metrics, PenetrationIsTheDepthOnTheSmallerAxis) {
  const Scene s = two_boxes({0, 0}, {0.9, 0.3});
  // Overlap 0.1 in x, 0.7 in y: depth 0.1.
  const PairOverlap o = MetricsRecorder::deepest_overlap(s, state({{0, 0}, {0.9, 0.3}}), 3);
  EXPECT_NEAR(o.depth, 0.1, 1e-12);
  EXPECT_EQ(o.a, 0u);
  EXPECT_EQ(o.b, 1u);
  EXPECT_EQ(o.step, 3);
  EXPECT_EQ(deepest(s, state({{0, 0}, {1.0, 0.0}})), 0.0);  // touching is not overlapping
}

TEST(Metrics, PenetrationIgnoresPairsOfImmovableBodies) {
  const Scene s = two_boxes({0, 0}, {0.5, 0}, BodyKind::kStatic);
  Scene statics = s;
  statics.bodies[0].kind = BodyKind::kStatic;
  EXPECT_EQ(deepest(statics, state({{0, 0}, {0.5, 0}})), 0.0);
  EXPECT_NEAR(deepest(s, state({{0, 0}, {0.5, 0}})), 0.5, 1e-12);
}

TEST(Metrics, PenetrationOfTurnedBoxesUsesTheirEdges) {
  Scene s = two_boxes({0, 0}, {1.2, 0});
  s.rotation = true;
  BodyState st = state({{0, 0}, {1.2, 0}});
  // b turned 45 degrees: its corner reaches sqrt(0.5) = 0.7071 towards a, whose face is at 0.5:
  // the boxes overlap by 0.5 + 0.7071 - 1.2 along x, the least of the four axes here.
  st.angle[1] = std::numbers::pi / 4.0;
  EXPECT_NEAR(deepest(s, st), 0.5 + std::sqrt(0.5) - 1.2, 1e-12);
  st.position[1].x = 1.25;  // 0.5 + 0.7071 < 1.25: apart
  EXPECT_EQ(deepest(s, st), 0.0);
}

// A scene of 400 boxes of mixed sizes on a wide ground, one of them 30 times bigger than the
// rest, some moving far in the step: the grid must report exactly the pairs whose swept boxes
// touch, each once.
TEST(Metrics, PairScanFindsExactlyThePairsWhoseSweptBoxesTouch) {
  Scene s;
  s.bodies.push_back({"ground", BodyKind::kStatic, {0, -1}, {4000, 1}, {}, 0, 1, {}, {}});
  s.bodies.push_back({"boulder", BodyKind::kDynamic, {5, 10}, {6, 6}, {}, 1, 1, {}, {}});
  for (int i = 0; i < 400; ++i) {
    const double x = -20 + 0.37 * (i % 100), y = 0.3 + 0.41 * (i / 100) + 0.01 * (i % 7);
    s.bodies.push_back(
        {"b", BodyKind::kDynamic, {x, y}, {0.2 + 0.05 * (i % 5), 0.25}, {}, 1, 1, {}, {}});
  }
  BodyState before(s.bodies.size()), after(s.bodies.size());
  for (std::size_t i = 0; i < s.bodies.size(); ++i) {
    before.position[i] = s.bodies[i].center;
    // Every 37th body flies 9 m in the step; the others creep.
    const double dx = i % 37 == 0 ? 9.0 : 0.01 * static_cast<double>(i % 3);
    after.position[i] = {s.bodies[i].center.x + dx, s.bodies[i].center.y - 0.02};
  }
  after.position[0] = before.position[0];
  PairScan scan(s);
  scan.build(before, after);
  std::set<std::pair<std::size_t, std::size_t>> found;
  std::size_t reports = 0;
  scan.for_each_pair([&](std::size_t i, std::size_t j) {
    ASSERT_LT(i, j);
    found.insert({i, j});
    ++reports;
  });
  EXPECT_EQ(reports, found.size()) << "a pair was reported twice";
  auto box = [&](std::size_t i) {
    const Vec2d h = s.bodies[i].half_extents, p = before.position[i], q = after.position[i];
    return std::array<double, 4>{std::min(p.x, q.x) - h.x, std::min(p.y, q.y) - h.y,
                                 std::max(p.x, q.x) + h.x, std::max(p.y, q.y) + h.y};
  };
  std::set<std::pair<std::size_t, std::size_t>> brute;
  for (std::size_t i = 0; i < s.bodies.size(); ++i) {
    for (std::size_t j = i + 1; j < s.bodies.size(); ++j) {
      if (s.bodies[i].kind != BodyKind::kDynamic && s.bodies[j].kind != BodyKind::kDynamic)
        continue;
      const auto a = box(i), b = box(j);
      if (a[0] <= b[2] && b[0] <= a[2] && a[1] <= b[3] && b[1] <= a[3]) brute.insert({i, j});
    }
  }
  EXPECT_GT(brute.size(), 1000u);
  EXPECT_EQ(found, brute);
}

// A body crossing a thin static slab in one step, and one sinking through it over several steps,
// went through it; a body pressed in and pushed back out of the face it came in by, one sliding
// off the slab's side, and one created inside it did not.
TEST(Tunnelling, IsLeavingThroughTheFaceOppositeTheOneEnteredBy) {
  Scene s = two_boxes({0, 2}, {0, 0}, BodyKind::kStatic);
  s.bodies[1].half_extents = {2.0, 0.05};  // a slab 0.1 m thick, top at y = 0.05
  auto watch = [&](std::vector<Vec2d> path) {
    TunnelWatch w(s);
    for (std::size_t k = 1; k < path.size(); ++k) {
      w.check(state({path[k - 1], {0, 0}}), state({path[k], {0, 0}}), 0, 1, static_cast<int>(k));
      w.end_step();
    }
    return w;
  };
  const TunnelWatch fast = watch({{0, 2}, {0, -2}});  // 4 m in one step, straight through
  ASSERT_TRUE(fast.first().has_value());
  EXPECT_EQ(fast.first()->body, 0u);
  EXPECT_EQ(fast.first()->through, 1u);
  EXPECT_EQ(fast.first()->step, 1);
  EXPECT_EQ(watch({{0, 0.6}, {0, 0.5}, {0, 0.2}, {0, -0.2}, {0, -0.6}}).count(), 1u);  // sank
  EXPECT_EQ(watch({{0, 0.6}, {0, 0.5}, {0, 0.3}, {0, 0.55}, {0, 0.7}}).count(), 0u);   // out on top
  EXPECT_EQ(watch({{1.9, 0.6}, {1.9, 0.5}, {3.0, 0.5}, {3.0, -1.0}}).count(), 0u);  // off the side
  EXPECT_EQ(watch({{0, 0.0}, {0, -0.2}, {0, -0.6}}).count(), 0u);  // created inside: not judged
  EXPECT_EQ(watch({{0, 0.55}, {0, 0.55}}).count(), 0u);            // resting on it, touching
}

// A box that catches another's corner and slides down its side, 0.1 m into it, has not passed
// through it: it never had half of itself across the other's middle. One sinking straight
// through has.
TEST(Tunnelling, GrazingACornerAndSlidingDownTheSideIsNotPassingThrough) {
  const Scene s = two_boxes({-0.9, 1.1}, {0, 0}, BodyKind::kStatic);
  auto count = [&](double x) {
    TunnelWatch w(s);
    const std::vector<Vec2d> path = {{x, 1.1}, {x, 0.95}, {x, 0.3}, {x, -0.4}, {x, -1.1}};
    for (std::size_t k = 1; k < path.size(); ++k) {
      w.check(state({path[k - 1], {0, 0}}), state({path[k], {0, 0}}), 0, 1, static_cast<int>(k));
      w.end_step();
    }
    return w.count();
  };
  EXPECT_EQ(count(-0.9), 0u);  // along the side, 0.1 m in
  EXPECT_EQ(count(-0.6), 0u);  // 0.4 m in: less than half of itself across
  EXPECT_EQ(count(-0.4), 1u);  // more than half across the middle: through
}

TEST(Tunnelling, IsJudgedOnTheRelativeMotionOfTwoMovingBodies) {
  const Scene s = two_boxes({-3, 0}, {3, 0});
  TunnelWatch w(s);
  // Both move 4 m towards each other and end on the other's side: each passed through the other.
  w.check(state({{-3, 0}, {3, 0}}), state({{1, 0}, {-1, 0}}), 0, 1, 1);
  w.end_step();
  EXPECT_EQ(w.count(), 1u);
  // Moving together side by side is not crossing.
  TunnelWatch side(s);
  side.check(state({{0, 0}, {1, 0}}), state({{5, 0}, {6, 0}}), 0, 1, 1);
  side.end_step();
  EXPECT_EQ(side.count(), 0u);
}

// Penetration is judged per pair against 5% of the pair's smaller box (or the scene's own
// tolerance), and a pair created overlapping may stay as deep as it started.
TEST(Metrics, PenetrationIsJudgedAgainstItsTolerance) {
  Scene s = two_boxes({0, 0}, {0.9, 0});
  s.bodies[1].half_extents = {0.25, 0.25};  // smaller box 0.5 m: 2.5 cm may overlap
  s.bodies[1].center = {1.0, 0.0};
  auto worst = [&](const Scene& scene, Vec2d b_after) {
    MetricsRecorder m(scene, MetricSelection{false, true, false});
    const BodyState start = initial_state(scene);
    m.observe(start, state({{0, 0}, b_after}), 1, false);
    return m.result(state({{0, 0}, b_after})).worst_overlap;
  };
  const auto shallow = worst(s, {0.73, 0});  // 2 cm
  ASSERT_TRUE(shallow.has_value());
  EXPECT_NEAR(shallow->depth, 0.02, 1e-12);
  EXPECT_NEAR(shallow->tolerance, 0.025, 1e-12);
  EXPECT_NEAR(worst(s, {0.7, 0})->depth, 0.05, 1e-12);
  Scene strict = s;
  strict.penetration_tolerance = 0.001;
  EXPECT_NEAR(worst(strict, {0.73, 0})->tolerance, 0.001, 1e-15);
  Scene created = s;
  created.bodies[1].center = {0.6, 0.0};  // starts 0.15 m deep
  EXPECT_NEAR(worst(created, {0.65, 0})->tolerance, 0.15, 1e-12);
}

TEST(Metrics, StabilityMeasuresSpeedFromPositionsAndJudgesEachBodysReach) {
  Scene s = two_boxes({0, 0}, {5, 0});
  s.gravity = {0, -10};  // bound: 1.25 * (0 + 0 + 10 * 0.1 * 10) + 1 = 13.5 m/s
  {
    MetricsRecorder m(s, MetricSelection{false, false, true});
    // a moves 1.3 m in the 0.1 s step: 13 m/s, whatever its velocity says.
    const BodyState end = state({{0, -1.3}, {5, 0}});
    m.observe(state({{0, 0}, {5, 0}}), end, 1, false);
    const Metrics r = m.result(end);
    EXPECT_NEAR(*r.speed_bound, 13.5, 1e-12);
    EXPECT_TRUE(*r.finite && *r.in_bounds && !*r.blow_up && !*r.tunnelled);
    EXPECT_NEAR(*r.peak_speed, 13.0, 1e-12);
    EXPECT_EQ(r.peak_speed_body, 0u);
    EXPECT_EQ(r.peak_speed_step, 1);
  }
  {
    // 2 m in a 0.1 s step is 0.65 m beyond what 13.5 m/s allows, far above the 5 cm (5% of the
    // smallest box) a body may travel beyond the bound.
    MetricsRecorder m(s, MetricSelection{false, false, true});
    const BodyState end = state({{2.0, 0}, {5, 0}});
    m.observe(state({{0, 0}, {5, 0}}), end, 1, false);
    const Metrics r = m.result(end);
    EXPECT_TRUE(*r.blow_up);
    EXPECT_EQ(r.blow_up_body, 0u);
    EXPECT_EQ(r.blow_up_step, 1);
    EXPECT_NEAR(r.blow_up_speed, 20.0, 1e-9);
  }
  {
    // A step 4 cm beyond the bound, then slower steps that give it back, again and again (a float
    // engine far from the origin moving in steps of its resolution): never 5 cm beyond over any
    // stretch of steps, so no blow-up. Without the slow steps in between it adds up to one.
    for (const bool rests : {true, false}) {
      MetricsRecorder m(s, MetricSelection{false, false, true});
      BodyState at = state({{0, 0}, {5, 0}});
      for (int k = 1; k <= 20; ++k) {
        const bool jump = !rests || k % 2 == 1;
        BodyState next = state({{at.position[0].x + (jump ? 1.39 : 0.0), 0}, {5, 0}});
        m.observe(at, next, k, false);
        at = next;
      }
      EXPECT_EQ(*m.result(at).blow_up, !rests) << rests;
    }
  }
  // Each body may get as far as its speed bound over the run, 13.5 m/s for 1 s, plus 5% of the
  // smallest box and twice the largest half diagonal: 14.96 m.
  for (const double x : {14.5, 15.5}) {
    MetricsRecorder m(s, MetricSelection{false, false, true});
    const BodyState end = state({{0, 0}, {5 + x, 0}});
    const Metrics r = m.result(end);
    EXPECT_EQ(*r.in_bounds, x < 14.96) << x;
    EXPECT_EQ(r.escaped.size(), x < 14.96 ? 0u : 1u) << x;
  }
  {
    MetricsRecorder m(s, MetricSelection{false, false, true});
    const BodyState end = state({{std::numeric_limits<double>::quiet_NaN(), 0}, {5, 0}});
    m.observe(state({{0, 0}, {5, 0}}), end, 1, false);
    EXPECT_FALSE(*m.result(end).finite);
  }
}

// Bounces bound speed by energy, not by the fastest body: a 1 kg box on a 100 kg one, both falling
// for 1 s onto a floor, may leave at nearly three times the fall speed, and must not be called a
// blow-up for it.
TEST(MotionBounds, BouncesAreBoundedByEnergy) {
  Scene s;
  s.dt = 0.1;
  s.steps = 10;
  s.restitution = 1.0;
  s.bodies.push_back({"floor", BodyKind::kStatic, {0, -0.5}, {5, 0.5}, {}, 0, 1, {}, {}});
  s.bodies.push_back({"big", BodyKind::kDynamic, {0, 5.5}, {0.5, 0.5}, {}, 100, 1, {}, {}});
  s.bodies.push_back({"small", BodyKind::kDynamic, {0, 7.25}, {0.25, 0.25}, {}, 1, 1, {}, {}});
  const MotionBounds b = motion_bounds(s);
  // Energy: both fall for 1 s at 10 m/s^2, 1/2 * 101 * 10^2 = 5050 J, all of which the small box
  // could take: sqrt(2 * 5050 / 1) = 100.5 m/s, a quarter more and 1 m/s.
  EXPECT_NEAR(b.speed[2], 1.25 * std::sqrt(2.0 * 5050.0) + 1.0, 1e-9);
  EXPECT_NEAR(b.speed[1], 1.25 * std::sqrt(2.0 * 5050.0 / 100.0) + 1.0, 1e-9);
  EXPECT_GT(b.speed[2], 3.0 * 10.0);  // the elastic answer, 29.6 m/s, is within it
  EXPECT_TRUE(b.unbounded.empty());
  // Without bounces, nothing moves faster than the fastest thing in the scene could make it.
  s.restitution = 0.0;
  EXPECT_NEAR(motion_bounds(s).speed[2], 1.25 * 10.0 + 1.0, 1e-9);
}

// The speed bound comes from what the scene can give, not from how long it runs: in a 3 s scene
// whose crate has 1.5 m to fall onto a wide floor and whose crusher moves at 1 m/s, nothing can
// move faster than sqrt(2 * 10 * 1.5) + 1 = 6.5 m/s (bound 1.25 * 6.5 + 1 = 9.1 m/s). An engine
// throwing the squeezed crate at 14 m/s blew up; a fall of 30 m/s, what 3 s of falling would
// allow, cannot happen here. The same bound holds however long the run.
TEST(MotionBounds, SpeedComesFromTheHeightToFallAndTheDrivesNotTheRunsLength) {
  Scene s;
  s.dt = 1.0 / 60.0;
  s.steps = 180;
  s.bodies.push_back({"floor", BodyKind::kStatic, {0, -0.5}, {20, 0.5}, {}, 0, 1, {}, {}});
  s.bodies.push_back({"crate", BodyKind::kDynamic, {0, 2.0}, {0.5, 0.5}, {}, 1, 1, {}, {}});
  s.bodies.push_back(
      {"crusher", BodyKind::kKinematic, {-3, 0.5}, {0.5, 0.5}, {1, 0}, 0, 1, {}, {}});
  const double bound = 1.25 * (std::sqrt(2.0 * 10.0 * 1.5) + 1.0) + 1.0;
  EXPECT_NEAR(motion_bounds(s).speed[1], bound, 1e-9);
  // However long the run, on a floor wide enough that the crusher cannot push the crate off it.
  Scene longer = s;
  longer.steps = 3600;  // 60 s: 60 m of crusher travel
  longer.bodies[0].half_extents.x = 100;
  EXPECT_NEAR(motion_bounds(longer).speed[1], bound, 1e-9);
  auto thrown = [&](double speed) {
    MetricsRecorder m(s, MetricSelection{false, false, true});
    BodyState at = state({{0, -0.5}, {0, 2.0}, {-3, 0.5}});
    for (int k = 1; k <= 3; ++k) {
      BodyState next = at;
      next.position[1].x += speed * s.dt;
      next.position[2].x += 1.0 * s.dt;
      m.observe(at, next, k, false);
      at = next;
    }
    return m.result(at);
  };
  const Metrics fast = thrown(14.0);
  EXPECT_TRUE(*fast.blow_up);
  EXPECT_EQ(fast.blow_up_body, 1u);
  EXPECT_NEAR(fast.blow_up_bound, bound, 1e-9);
  EXPECT_FALSE(*thrown(6.0).blow_up);  // as fast as the fall and the crusher together: physics
  // A crusher moving up can lift the crate 3 m higher before it falls: sqrt(2 * 10 * 4.5).
  Scene lifting = s;
  lifting.bodies[2].velocity = {0, 1};
  EXPECT_NEAR(motion_bounds(lifting).speed[1], 1.25 * (std::sqrt(90.0) + 1.0) + 1.0, 1e-9);
  // With the floor too narrow to be sure the crate stays on it, the fall lasts the run.
  Scene narrow = s;
  narrow.bodies[0].half_extents.x = 2.0;
  EXPECT_NEAR(motion_bounds(narrow).speed[1], 1.25 * (10.0 * 3.0 + 1.0) + 1.0, 1e-9);
}

// Bounces off a moving paddle add its speed twice each time: such a scene bounds no speed, and no
// speed in it is a blow-up.
TEST(MotionBounds, BouncesOffAMovingKinematicBodyAreUnbounded) {
  Scene s = two_boxes({0, 0}, {3, 0}, BodyKind::kKinematic);
  s.bodies[1].velocity = {-2, 0};
  s.restitution = 1.0;
  const MotionBounds b = motion_bounds(s);
  EXPECT_FALSE(b.unbounded.empty());
  EXPECT_TRUE(std::isinf(b.speed[0]));
  MetricsRecorder m(s, MetricSelection{false, false, true});
  const BodyState end = state({{10, 0}, {3, 0}});  // 100 m/s in a 0.1 s step
  m.observe(state({{0, 0}, {3, 0}}), end, 1, false);
  const Metrics r = m.result(end);
  EXPECT_FALSE(*r.blow_up);
  EXPECT_FALSE(r.speed_bound.has_value());
  EXPECT_FALSE(r.speed_unbounded.empty());
}

// Overlaps a scene starts with may push the bodies of their cluster beyond their speed, but not a
// body far away: a projectile is judged on its own however many crates overlap elsewhere.
TEST(MotionBounds, StartingOverlapsExcuseOnlyTheirOwnCluster) {
  Scene s = two_boxes({0, 0}, {0.6, 0});  // 0.4 m into each other
  s.bodies.push_back({"far", BodyKind::kDynamic, {100, 0}, {0.5, 0.5}, {}, 1, 1, {}, {}});
  const MotionBounds b = motion_bounds(s);
  EXPECT_NEAR(b.allowance[0], 0.4 + 0.05, 1e-12);
  EXPECT_NEAR(b.allowance[1], 0.4 + 0.05, 1e-12);
  EXPECT_NEAR(b.allowance[2], 0.05, 1e-12);
  EXPECT_NEAR(b.initial_depth[0], 0.4, 1e-12);
  EXPECT_EQ(b.initial_overlaps.size(), 1u);
}

// A body pushed out of an overlap it was in moves without speed. Two boxes meet head-on at 12 m/s
// each (bound 1.25 * 12 + 1 = 16 m/s, 0.267 m a step at 60 Hz) and end a step 0.2 m into each
// other; pushing them 0.35 m apart the next step, as Box2D's position correction does, is not a
// blow-up. The same 0.35 m with nothing to push out of is.
TEST(Metrics, APushOutOfAnOverlapIsNotABlowUp) {
  Scene s = two_boxes({-0.6, 0}, {0.6, 0});
  s.dt = 1.0 / 60.0;
  s.bodies[0].velocity = {12, 0};
  s.bodies[1].velocity = {-12, 0};
  for (const bool overlapped : {true, false}) {
    MetricsRecorder m(s, MetricSelection{false, false, true});
    const BodyState start = state({{-0.6, 0}, {0.6, 0}});
    // 0.2 m deep, or stopped short of each other.
    const BodyState met = overlapped ? state({{-0.4, 0}, {0.4, 0}}) : state({{-0.6, 0}, {0.6, 0}});
    const BodyState pushed = state({{met.position[0].x - 0.35, 0}, {met.position[1].x + 0.35, 0}});
    m.observe(start, met, 1, false);
    m.observe(met, pushed, 2, false);
    EXPECT_EQ(*m.result(pushed).blow_up, !overlapped) << overlapped;
  }
}

TEST(Metrics, FiguresWithinTwoUlpsOfTheirMagnitudeAreRounding) {
  EXPECT_TRUE(below_resolution(8.881784197001252e-16, 4.0));  // one ulp at 4 m
  EXPECT_TRUE(below_resolution(1.7e-15, 4.0));
  EXPECT_FALSE(below_resolution(1e-14, 4.0));
  EXPECT_FALSE(below_resolution(1e-12, 1000.0));
  EXPECT_TRUE(below_resolution(1e-13, 1e6));
  EXPECT_FALSE(below_resolution(HUGE_VAL, 1.0));
  const Scene s = two_boxes({4, 0}, {5, 0});
  const std::vector<Vec2d> ref = {{4.0, 0.0}, {5.0, 0.0}};
  const std::vector<Vec2d> run = {{std::nextafter(4.0, 5.0), 0.0}, {5.0, 0.0}};
  EXPECT_EQ(position_error(s, run, ref).max, 0.0);
}

TEST(Metrics, HashIsFnv1aOverThePositionBits) {
  EXPECT_EQ(position_hash({}), 0xcbf29ce484222325ull);  // the FNV offset basis
  const std::vector<Vec2d> a = {{1.0, 2.0}}, b = {{1.0, 2.0000000000000004}}, c = {{2.0, 1.0}};
  EXPECT_NE(position_hash(a), position_hash(b));  // one ulp apart
  EXPECT_NE(position_hash(a), position_hash(c));
  EXPECT_EQ(position_hash(a), position_hash(std::vector<Vec2d>{{1.0, 2.0}}));
  EXPECT_EQ(hex(0x9f3cull), "0000000000009f3c");
}

TEST(Metrics, PositionErrorIsMaxAndRmsOverDynamicBodies) {
  Scene s = two_boxes({0, 0}, {5, 0});
  s.bodies.push_back({"wall", BodyKind::kStatic, {9, 0}, {0.5, 0.5}, {}, 0, 1, {}, {}});
  const std::vector<Vec2d> ref = {{0, 0}, {5, 0}, {9, 0}};
  const std::vector<Vec2d> run = {{3, 4}, {5, 0}, {100, 0}};  // the static's error does not count
  const PositionError e = position_error(s, run, ref);
  EXPECT_DOUBLE_EQ(e.max, 5.0);
  EXPECT_DOUBLE_EQ(e.rms, std::sqrt(25.0 / 2.0));
}

TEST(Metrics, SelectionParsesNamesAndRefusesOthers) {
  EXPECT_FALSE(parse_metric_selection("none").any());
  const MetricSelection s = parse_metric_selection("penetration,stability");
  EXPECT_TRUE(s.penetration && s.stability && !s.displacement);
  EXPECT_THROW(parse_metric_selection("speed"), std::exception);
}

}  // namespace
}  // namespace chainbench
