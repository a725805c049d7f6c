// Each metric on cases small enough to compute by hand.
#include "metrics.h"
#include "overlap_scan.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

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
  m.observe(state({{0, 0}, {5, 0}}), state({{0.3, 0}, {5, 0.4}}, {{2, 0}, {0, 0}}), true);
  m.observe(state({{0.3, 0}, {5, 0.4}}, {{2, 0}, {0, 0}}),
            state({{0.5, 0}, {5, 0.4}}, {{2, 0}, {0, 0}}), false);
  const Metrics r = m.result();
  EXPECT_NEAR(*r.efd_total, 0.1 + 0.4, 1e-12);
  EXPECT_NEAR(*r.efd_max_step, 0.4, 1e-12);
  EXPECT_NEAR(*r.efd_per_body_step, 0.5 / 4.0, 1e-12);  // 2 bodies x 2 steps
  EXPECT_FALSE(r.max_penetration.has_value());          // not asked for
  EXPECT_FALSE(r.finite.has_value());
}

TEST(Metrics, PenetrationIsTheDepthOnTheSmallerAxis) {
  const Scene s = two_boxes({0, 0}, {0.9, 0.3});
  OverlapScan scan(s);
  std::vector<double> per_body(2);
  // Overlap 0.1 in x, 0.7 in y: depth 0.1.
  EXPECT_NEAR(scan.deepest(state({{0, 0}, {0.9, 0.3}}), per_body), 0.1, 1e-12);
  EXPECT_NEAR(per_body[0], 0.1, 1e-12);
  EXPECT_NEAR(per_body[1], 0.1, 1e-12);
  EXPECT_EQ(scan.deepest(state({{0, 0}, {1.0, 0.0}}), {}), 0.0);  // touching is not overlapping
}

TEST(Metrics, PenetrationIgnoresPairsOfImmovableBodies) {
  const Scene s = two_boxes({0, 0}, {0.5, 0}, BodyKind::kStatic);
  Scene statics = s;
  statics.bodies[0].kind = BodyKind::kStatic;
  EXPECT_EQ(OverlapScan(statics).deepest(state({{0, 0}, {0.5, 0}}), {}), 0.0);
  EXPECT_NEAR(OverlapScan(s).deepest(state({{0, 0}, {0.5, 0}}), {}), 0.5, 1e-12);
}

TEST(Metrics, PenetrationOfTurnedBoxesUsesTheirEdges) {
  Scene s = two_boxes({0, 0}, {1.2, 0});
  s.rotation = true;
  BodyState st = state({{0, 0}, {1.2, 0}});
  // b turned 45 degrees: its corner reaches sqrt(0.5) = 0.7071 towards a, whose face is at 0.5:
  // the boxes overlap by 0.5 + 0.7071 - 1.2 along x, the least of the four axes here.
  st.angle[1] = std::numbers::pi / 4.0;
  EXPECT_NEAR(OverlapScan(s).deepest(st, {}), 0.5 + std::sqrt(0.5) - 1.2, 1e-12);
  st.position[1].x = 1.25;  // 0.5 + 0.7071 < 1.25: apart
  EXPECT_EQ(OverlapScan(s).deepest(st, {}), 0.0);
}

TEST(Metrics, PenetrationScanMatchesBruteForceOnAManyBodyScene) {
  Scene s;
  s.bodies.push_back({"ground", BodyKind::kStatic, {0, -1}, {40, 1}, {}, 0, 1, {}, {}});
  BodyState st(1);
  st.position[0] = {0, -1};
  for (int i = 0; i < 400; ++i) {
    const double x = -20 + 0.37 * (i % 100), y = 0.3 + 0.41 * (i / 100) + 0.01 * (i % 7);
    s.bodies.push_back(
        {"b", BodyKind::kDynamic, {x, y}, {0.2 + 0.05 * (i % 5), 0.25}, {}, 1, 1, {}, {}});
    st.position.push_back({x, y});
    st.velocity.push_back({});
    st.angle.push_back(0.0);
  }
  double brute = 0.0;
  for (std::size_t i = 0; i < s.bodies.size(); ++i) {
    for (std::size_t j = i + 1; j < s.bodies.size(); ++j) {
      if (s.bodies[i].kind != BodyKind::kDynamic && s.bodies[j].kind != BodyKind::kDynamic)
        continue;
      const double ox = s.bodies[i].half_extents.x + s.bodies[j].half_extents.x -
                        std::abs(st.position[i].x - st.position[j].x);
      const double oy = s.bodies[i].half_extents.y + s.bodies[j].half_extents.y -
                        std::abs(st.position[i].y - st.position[j].y);
      if (ox > 0 && oy > 0) brute = std::max(brute, std::min(ox, oy));
    }
  }
  EXPECT_GT(brute, 0.0);
  EXPECT_DOUBLE_EQ(OverlapScan(s).deepest(st, {}), brute);
}

TEST(Metrics, StabilityFlagsNaNFlightAndBlowUp) {
  Scene s = two_boxes({0, 0}, {5, 0});
  s.gravity = {0, -10};  // bound: 1.25 * (0 + 0 + 10 * 0.1 * 10) + 1 = 13.5 m/s
  {
    MetricsRecorder m(s, MetricSelection{false, false, true});
    m.observe(state({{0, 0}, {5, 0}}), state({{0, 0}, {5, 0}}, {{0, -13}, {0, 0}}), false);
    const Metrics r = m.result();
    EXPECT_NEAR(*r.speed_bound, 13.5, 1e-12);
    EXPECT_TRUE(*r.finite && *r.in_bounds && !*r.blow_up);
    EXPECT_NEAR(*r.peak_speed, 13.0, 1e-12);
  }
  {
    MetricsRecorder m(s, MetricSelection{false, false, true});
    m.observe(state({{0, 0}, {5, 0}}), state({{0, 0}, {5, 0}}, {{14, 0}, {0, 0}}), false);
    EXPECT_TRUE(*m.result().blow_up);
  }
  {
    MetricsRecorder m(s, MetricSelection{false, false, true});
    // The scene spans 6 x 1 m: 10 times its half diagonal from its centre is about 30 m.
    m.observe(state({{0, 0}, {5, 0}}), state({{0, 0}, {50, 0}}), false);
    EXPECT_FALSE(*m.result().in_bounds);
  }
  {
    MetricsRecorder m(s, MetricSelection{false, false, true});
    m.observe(state({{0, 0}, {5, 0}}),
              state({{std::numeric_limits<double>::quiet_NaN(), 0}, {5, 0}}), false);
    EXPECT_FALSE(*m.result().finite);
  }
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
