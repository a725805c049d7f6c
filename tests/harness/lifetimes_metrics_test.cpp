// SPDX-License-Identifier: MIT
// The metrics see a body only while it is in the world (metrics.h, presence.h): a scene whose
// bodies come and go gives the figures of the same scene with only the bodies present, whatever
// the states hold for a body outside its life (deep in the floor, inside a moving box, thrown far
// away, not finite), on every path the recorder takes (finding the moved bodies itself, told
// which changed, scanning every body); a body entering is no move, no blow-up and no tunnelling;
// a body leaving and one entering in its place in the state between them never overlap.
#include "index/presence.h"
#include "judge/metrics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace chainbench {
namespace {

constexpr int kSteps = 40;
constexpr double kDt = 1.0 / 60.0;

SceneBody body(const char* name, BodyKind kind, Vec2d center, Vec2d half) {
  SceneBody b;
  b.name = name;
  b.kind = kind;
  b.center = center;
  b.half_extents = half;
  return b;
}

// The bodies there throughout: a floor, a box resting 1 cm into it whose height wobbles by
// 0.1 mm each step with no velocity (an energy-free displacement every step), and a box
// sliding right at 1 m/s as its velocity says (none).
Scene base_scene() {
  Scene s;
  s.name = "base";
  s.dt = kDt;
  s.steps = kSteps;
  s.gravity = {0.0, -10.0};
  s.bodies.push_back(body("floor", BodyKind::kStatic, {0.0, -0.5}, {20.0, 0.5}));
  s.bodies.push_back(body("rest", BodyKind::kDynamic, {-3.0, 0.49}, {0.5, 0.5}));
  s.bodies.push_back(body("slide", BodyKind::kDynamic, {3.0, 0.5}, {0.5, 0.5}));
  s.bodies[2].velocity = {1.0, 0.0};
  return s;
}

// The base scene and two visitors: "guest" in the world in states 10..20, at rest where it
// enters and apart from everything; "late" in states 25..30 likewise.
Scene visited_scene() {
  Scene s = base_scene();
  s.name = "visited";
  s.bodies.push_back(body("guest", BodyKind::kDynamic, {0.0, 0.5}, {0.5, 0.5}));
  s.bodies.back().from_step = 10, s.bodies.back().to_step = 20;
  s.bodies.push_back(body("late", BodyKind::kDynamic, {-6.0, 0.5}, {0.5, 0.5}));
  s.bodies.back().from_step = 25, s.bodies.back().to_step = 30;
  return s;
}

// State k of `s`: the base bodies as base_scene() says; each visitor where it entered while in
// the world, and outside its life whatever `garbage` puts there.
BodyState state_of(const Scene& s, int k, int garbage) {
  BodyState st(s.bodies.size());
  st.position[0] = s.bodies[0].center;
  st.position[1] = {-3.0, k % 2 ? 0.4901 : 0.49};
  st.position[2] = {3.0 + k * kDt, 0.5};
  st.velocity[2] = {1.0, 0.0};
  for (std::size_t i = 3; i < s.bodies.size(); ++i) {
    const SceneBody& b = s.bodies[i];
    if (b.alive(k)) {
      st.position[i] = b.center;
      continue;
    }
    const double nan = std::numeric_limits<double>::quiet_NaN();
    switch (garbage) {
      case 0:  // deep in the floor, which it would overlap by its whole size
        st.position[i] = {0.0, -0.5};
        break;
      case 1:  // inside the sliding box, moving with it (it would pass through the floor too)
        st.position[i] = st.position[2];
        st.velocity[i] = {1.0, -300.0};
        break;
      case 2:  // thrown far away, a new place every state
        st.position[i] = {1e6 * k, -1e6 * k};
        break;
      default:  // not finite
        st.position[i] = {nan, nan};
        st.velocity[i] = {nan, nan};
    }
  }
  return st;
}

// The bodies whose state differs between two states, ascending (what StateFeed lists).
std::vector<std::uint32_t> changes(const BodyState& a, const BodyState& b) {
  std::vector<std::uint32_t> out;
  auto differs = [](double x, double y) { return !(x == y) && !(std::isnan(x) && std::isnan(y)); };
  for (std::size_t i = 0; i < a.position.size(); ++i) {
    if (differs(a.position[i].x, b.position[i].x) || differs(a.position[i].y, b.position[i].y) ||
        differs(a.velocity[i].x, b.velocity[i].x) || differs(a.velocity[i].y, b.velocity[i].y))
      out.push_back(static_cast<std::uint32_t>(i));
  }
  return out;
}

struct Recorded {
  Metrics m;
  std::vector<std::vector<double>> penetration;  // per step, the base bodies' step_penetration
  std::vector<double> deepest;                   // per step, last_deepest().depth
};

// mode 0: the recorder finds the moved bodies; 1: it is told which changed; 2: it scans every
// body every step.
Recorded record(const Scene& s, int garbage, int mode) {
  MetricsRecorder rec(s, MetricSelection{});
  if (mode == 2) rec.scan_every_body();
  Recorded r;
  BodyState before = state_of(s, 0, garbage);
  for (int k = 1; k <= kSteps; ++k) {
    const BodyState after = state_of(s, k, garbage);
    const std::vector<std::uint32_t> changed = changes(before, after);
    rec.observe(before, after, k, true, true, mode == 1 ? &changed : nullptr);
    r.penetration.emplace_back(rec.step_penetration().begin(), rec.step_penetration().begin() + 3);
    r.deepest.push_back(rec.last_deepest().depth);
    for (std::size_t i = 3; i < s.bodies.size(); ++i) {
      EXPECT_EQ(rec.step_penetration()[i], 0.0) << s.bodies[i].name << " at state " << k;
      if (!s.bodies[i].alive(k) || !s.bodies[i].alive(k - 1)) {
        EXPECT_EQ(rec.step_displacement()[i], 0.0) << s.bodies[i].name << " at state " << k;
      }
    }
    before = after;
  }
  r.m = rec.result(before);
  return r;
}

class LifetimeMetrics : public ::testing::TestWithParam<std::tuple<int, int>> {};

TEST_P(LifetimeMetrics, AreThoseOfTheSceneWithOnlyTheBodiesPresent) {
  const auto [garbage, mode] = GetParam();
  const Scene base = base_scene(), visited = visited_scene();
  const Recorded a = record(base, garbage, mode), b = record(visited, garbage, mode);
  // Every figure but the mean over body-steps is the base scene's, to the bit: the visitors sit
  // still apart from everything while they are in the world.
  ASSERT_TRUE(a.m.max_penetration && b.m.max_penetration);
  EXPECT_EQ(*b.m.max_penetration, *a.m.max_penetration);
  EXPECT_NEAR(*a.m.max_penetration, 0.01, 1e-12);  // the resting box, 1 cm into the floor
  ASSERT_TRUE(a.m.worst_overlap && b.m.worst_overlap);
  EXPECT_EQ(b.m.worst_overlap->a, a.m.worst_overlap->a);
  EXPECT_EQ(b.m.worst_overlap->b, a.m.worst_overlap->b);
  EXPECT_EQ(b.m.worst_overlap->depth, a.m.worst_overlap->depth);
  EXPECT_EQ(b.m.worst_overlap->step, a.m.worst_overlap->step);
  EXPECT_EQ(*b.m.efd_total, *a.m.efd_total);
  EXPECT_GT(*a.m.efd_total, 0.0);
  EXPECT_EQ(*b.m.efd_max_step, *a.m.efd_max_step);
  EXPECT_EQ(*b.m.peak_speed, *a.m.peak_speed);
  EXPECT_EQ(b.m.peak_speed_body, a.m.peak_speed_body);
  EXPECT_TRUE(*b.m.finite);
  EXPECT_FALSE(*b.m.blow_up);
  EXPECT_FALSE(*b.m.tunnelled);
  EXPECT_EQ(b.m.tunnel_count, 0u);
  EXPECT_TRUE(*b.m.in_bounds);
  EXPECT_TRUE(b.m.escaped.empty());
  EXPECT_EQ(b.penetration, a.penetration);
  EXPECT_EQ(b.deepest, a.deepest);
  // The mean is over the body-steps taken: 2 bodies for 40 steps, the guest for steps 10..19 and
  // the late one for steps 25..29 (a step k - 1 -> k counts a body in both states).
  EXPECT_DOUBLE_EQ(*a.m.efd_per_body_step, *a.m.efd_total / 80.0);
  EXPECT_DOUBLE_EQ(*b.m.efd_per_body_step, *b.m.efd_total / (80.0 + 10.0 + 5.0));
}

INSTANTIATE_TEST_SUITE_P(Garbage, LifetimeMetrics,
                         ::testing::Combine(::testing::Values(0, 1, 2, 3),
                                            ::testing::Values(0, 1, 2)));

// A visitor that enters overlapping the resting box and one that leaves from inside the floor
// count in the states they are in, and only there.
TEST(LifetimeMetricsDepth, AnOverlapCountsOnlyInTheStatesOfTheBodysLife) {
  Scene s = base_scene();
  s.bodies.push_back(body("intruder", BodyKind::kDynamic, {-3.0, 1.29}, {0.5, 0.5}));
  s.bodies.back().from_step = 10, s.bodies.back().to_step = 20;  // 0.2 m into the resting box
  MetricsRecorder rec(s, MetricSelection{});
  BodyState before = state_of(s, 0, 0);
  before.position[3] = {-3.0, -0.5};  // deep in the floor while absent
  for (int k = 1; k <= kSteps; ++k) {
    BodyState after = state_of(s, k, 0);
    if (!s.bodies[3].alive(k)) after.position[3] = {-3.0, -0.5};
    rec.observe(before, after, k, true, true);
    const double expected = k % 2 ? 0.2001 : 0.2;  // the resting box wobbles 0.1 mm up and down
    const double deepest = rec.last_deepest().depth;
    if (s.bodies[3].alive(k)) {
      EXPECT_NEAR(deepest, expected, 1e-9) << "state " << k;
      EXPECT_NEAR(rec.step_penetration()[3], expected, 1e-9) << "state " << k;
    } else {
      EXPECT_NEAR(deepest, k % 2 ? 0.0099 : 0.01, 1e-9) << "state " << k;
      EXPECT_EQ(rec.step_penetration()[3], 0.0) << "state " << k;
    }
    before = after;
  }
  const Metrics m = rec.result(before);
  EXPECT_NEAR(*m.max_penetration, 0.2001, 1e-9);
  // Entering 0.2 m deep is no blow-up: the recorder lets the push out of it count as free.
  EXPECT_FALSE(*m.blow_up);
  EXPECT_FALSE(*m.tunnelled);
}

// "leaver" is in states 0..20 and "heir" in states 20..40, in the same place: in state 20 both
// are in the world, but no step has them together (the runner removes the leaver before step
// 20), so they never overlap; the no-overlap expectation's scan agrees.
TEST(LifetimeMetricsDepth, ALeaverAndItsHeirInTheSamePlaceNeverMeet) {
  Scene s = base_scene();
  s.bodies.push_back(body("leaver", BodyKind::kDynamic, {0.0, 0.5}, {0.5, 0.5}));
  s.bodies.back().to_step = 20;
  s.bodies.push_back(body("heir", BodyKind::kDynamic, {0.0, 0.5}, {0.5, 0.5}));
  s.bodies.back().from_step = 20;
  MetricsRecorder rec(s, MetricSelection{});
  BodyState before = state_of(s, 0, 0);
  before.position[4] = {0.0, 0.5};  // where it will enter, overlapping the leaver wholly
  for (int k = 1; k <= kSteps; ++k) {
    BodyState after = state_of(s, k, 0);
    after.position[3] = after.position[4] = {0.0, 0.5};
    rec.observe(before, after, k, true, true);
    EXPECT_LT(rec.last_deepest().depth, 0.02) << "state " << k;
    EXPECT_LT(MetricsRecorder::deepest_overlap(s, after, k).depth, 0.02) << "state " << k;
    before = after;
  }
  const Metrics m = rec.result(before);
  EXPECT_NEAR(*m.max_penetration, 0.01, 1e-9);
  EXPECT_FALSE(*m.tunnelled);
}

// Presence follows the states one by one as it does after a jump.
TEST(Presence, FollowsStatesInOrderAsAfterAJump) {
  const Scene s = visited_scene();
  Presence walk(s);
  for (int k = 0; k <= kSteps; ++k) {
    walk.at(k);
    Presence jump(s);
    jump.at(k);
    std::size_t stepped = 0;
    for (std::size_t i = 0; i < s.bodies.size(); ++i) {
      EXPECT_EQ(walk.in(i), s.bodies[i].alive(k)) << i << " at " << k;
      EXPECT_EQ(walk.was(i), k == 0 ? s.bodies[i].alive(0) : s.bodies[i].alive(k - 1));
      EXPECT_EQ(jump.in(i), walk.in(i));
      EXPECT_EQ(jump.was(i), walk.was(i));
      stepped += walk.stepped(i);
    }
    EXPECT_EQ(walk.stepped_count(), stepped) << k;
    EXPECT_EQ(jump.stepped_count(), stepped) << k;
    EXPECT_EQ(walk.dynamic_stepped(), stepped - 1) << k;  // the floor is static
    EXPECT_EQ(std::vector<std::uint32_t>(walk.changed().begin(), walk.changed().end()),
              std::vector<std::uint32_t>(jump.changed().begin(), jump.changed().end()));
  }
}

}  // namespace
}  // namespace chainbench
