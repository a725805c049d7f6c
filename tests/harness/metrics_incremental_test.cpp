// SPDX-License-Identifier: MIT
// The metrics' shortcuts give the figures of a full scan: on random scenes in which every step
// moves no body, a few or most, the recorder that re-judges only the pairs with a moved body
// (told which bodies changed, or finding them itself) agrees to the bit with one that scans every
// body every step, and both with a brute-force pass
// over every pair (touching boxes, which do not overlap, and pairs of immovable bodies included).
#include "judge/metrics.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

namespace chainbench {
namespace {

// A field of boxes on a lattice whose neighbours touch exactly (the lattice pitch is the box
// size), some overlapping their neighbours, with a static floor across all of them, a static
// post and a kinematic block among them.
Scene random_scene(std::mt19937& rng, bool rotation) {
  Scene s;
  s.gravity = {0.0, -9.81};
  s.dt = 1.0 / 60.0;
  s.steps = 1000;
  s.rotation = rotation;
  s.bodies.push_back(
      {"floor", BodyKind::kStatic, {0.0, -1.0}, {4000.0, 1.0}, {}, 0.0, 1.0, {}, {}});
  s.bodies.push_back({"post", BodyKind::kStatic, {3.0, 2.0}, {0.5, 2.0}, {}, 0.0, 1.0, {}, {}});
  s.bodies.push_back(
      {"block", BodyKind::kKinematic, {-3.0, 3.0}, {1.0, 0.5}, {}, 0.0, 1.0, {}, {}});
  std::uniform_int_distribution<int> pick(0, 9);
  for (int row = 0; row < 12; ++row) {
    for (int col = 0; col < 25; ++col) {
      Vec2d c{-12.0 + col * 1.0, 0.5 + row * 1.0};
      if (pick(rng) == 0) c.x += 0.05;  // into its right neighbour
      if (pick(rng) == 0) c.y -= 0.03;  // into the one below
      SceneBody box;
      box.name = "box";
      box.center = c;
      s.bodies.push_back(box);
    }
  }
  return s;
}

// Steps a state: none, a few or most bodies move (a few far, through their neighbours), some keep
// still with a velocity, and the kinematic block slides.
BodyState next_state(std::mt19937& rng, const Scene& s, const BodyState& at, int kind) {
  BodyState next = at;
  std::uniform_real_distribution<double> jiggle(-0.02, 0.02), unit(0.0, 1.0);
  const double share = kind == 0 ? 0.0 : kind == 1 ? 0.05 : 0.6;
  for (std::size_t i = 0; i < s.bodies.size(); ++i) {
    next.velocity[i] = {};
    if (s.bodies[i].kind == BodyKind::kStatic || unit(rng) >= share) continue;
    if (s.bodies[i].kind == BodyKind::kKinematic) {
      next.position[i].x += 0.1;
      next.velocity[i] = {6.0, 0.0};
      continue;
    }
    const double far = unit(rng) < 0.05 ? 1.6 : 1.0;
    next.position[i].x += far == 1.0 ? jiggle(rng) : far;
    next.position[i].y += jiggle(rng);
    if (s.rotation) next.angle[i] += jiggle(rng);
    next.velocity[i] = {jiggle(rng) * 60.0, jiggle(rng) * 60.0};
  }
  if (kind != 0 && unit(rng) < 0.3) next.velocity[3] = {0.5, 0.0};  // a velocity, no move
  return next;
}

// Every pair's overlap by brute force, on boxes that do not turn: the deepest (the lowest pair of
// equal depths) and each body's deepest. Depths within rounding of their magnitude are none.
struct Brute {
  PairOverlap deepest;
  std::vector<double> per_body;
};
Brute brute_force(const Scene& s, const BodyState& st) {
  Brute b;
  b.per_body.assign(s.bodies.size(), 0.0);
  for (std::size_t i = 0; i < s.bodies.size(); ++i) {
    for (std::size_t j = i + 1; j < s.bodies.size(); ++j) {
      if (s.bodies[i].kind != BodyKind::kDynamic && s.bodies[j].kind != BodyKind::kDynamic)
        continue;
      const Vec2d hi = s.bodies[i].half_extents, hj = s.bodies[j].half_extents;
      const Vec2d p = st.position[i], q = st.position[j];
      const double ox = hi.x + hj.x - std::abs(p.x - q.x), oy = hi.y + hj.y - std::abs(p.y - q.y);
      if (ox <= 0.0 || oy <= 0.0) continue;  // apart, or touching
      const double d = std::min(ox, oy);
      const double scale = std::max({magnitude(p), magnitude(q), hi.x + hj.x, hi.y + hj.y});
      if (below_resolution(d, scale)) continue;
      if (d > b.deepest.depth) b.deepest.depth = d, b.deepest.a = i, b.deepest.b = j;
      b.per_body[i] = std::max(b.per_body[i], d);
      b.per_body[j] = std::max(b.per_body[j], d);
    }
  }
  return b;
}

void expect_same(const Metrics& a, const Metrics& b) {
  EXPECT_EQ(*a.efd_total, *b.efd_total);
  EXPECT_EQ(*a.efd_max_step, *b.efd_max_step);
  EXPECT_EQ(*a.max_penetration, *b.max_penetration);
  ASSERT_EQ(a.worst_overlap.has_value(), b.worst_overlap.has_value());
  if (a.worst_overlap) {
    EXPECT_EQ(a.worst_overlap->depth, b.worst_overlap->depth);
    EXPECT_EQ(a.worst_overlap->a, b.worst_overlap->a);
    EXPECT_EQ(a.worst_overlap->b, b.worst_overlap->b);
    EXPECT_EQ(a.worst_overlap->step, b.worst_overlap->step);
  }
  EXPECT_EQ(*a.peak_speed, *b.peak_speed);
  EXPECT_EQ(a.peak_speed_body, b.peak_speed_body);
  EXPECT_EQ(a.peak_speed_step, b.peak_speed_step);
  EXPECT_EQ(*a.blow_up, *b.blow_up);
  EXPECT_EQ(a.blow_up_body, b.blow_up_body);
  EXPECT_EQ(a.blow_up_step, b.blow_up_step);
  EXPECT_EQ(*a.finite, *b.finite);
  EXPECT_EQ(a.escaped, b.escaped);
  EXPECT_EQ(a.tunnel_count, b.tunnel_count);
  ASSERT_EQ(a.tunnel.has_value(), b.tunnel.has_value());
  if (a.tunnel) {
    EXPECT_EQ(a.tunnel->body, b.tunnel->body);
    EXPECT_EQ(a.tunnel->through, b.tunnel->through);
    EXPECT_EQ(a.tunnel->step, b.tunnel->step);
  }
}

void run_and_compare(bool rotation, unsigned seed) {
  std::mt19937 rng(seed);
  const Scene s = random_scene(rng, rotation);
  MetricsRecorder fast(s, MetricSelection{}), full(s, MetricSelection{});
  full.scan_every_body();
  BodyState at = initial_state(s);
  std::uniform_int_distribution<int> kind(0, 4);  // still, a few, a few, a few, most
  int kinds_seen[3] = {0, 0, 0};
  for (int step = 1; step <= 60; ++step) {
    const int r = kind(rng), k = r == 0 ? 0 : r < 4 ? 1 : 2;
    ++kinds_seen[k];
    const BodyState next = next_state(rng, s, at, k);
    const bool per_body = step % 3 == 0;
    if (seed % 2 == 1) {
      // As the chain engine's read says it: the bodies whose state changed.
      std::vector<std::uint32_t> changed;
      for (std::size_t i = 0; i < s.bodies.size(); ++i) {
        if (next.position[i].x != at.position[i].x || next.position[i].y != at.position[i].y ||
            next.velocity[i].x != at.velocity[i].x || next.velocity[i].y != at.velocity[i].y ||
            next.angle[i] != at.angle[i])
          changed.push_back(static_cast<std::uint32_t>(i));
      }
      fast.observe(at, next, step, per_body, false, &changed);
    } else {
      fast.observe(at, next, step, per_body);
    }
    full.observe(at, next, step, per_body);
    ASSERT_EQ(fast.last_deepest().depth, full.last_deepest().depth) << "step " << step;
    EXPECT_EQ(fast.last_deepest().a, full.last_deepest().a) << "step " << step;
    EXPECT_EQ(fast.last_deepest().b, full.last_deepest().b) << "step " << step;
    if (per_body) {
      const auto pen = fast.step_penetration(), efd = fast.step_displacement();
      EXPECT_TRUE(std::equal(pen.begin(), pen.end(), full.step_penetration().begin()))
          << "step " << step;
      EXPECT_TRUE(std::equal(efd.begin(), efd.end(), full.step_displacement().begin()))
          << "step " << step;
      if (!rotation) {
        const Brute b = brute_force(s, next);
        EXPECT_EQ(fast.last_deepest().depth, b.deepest.depth) << "step " << step;
        EXPECT_EQ(fast.last_deepest().a, b.deepest.a) << "step " << step;
        EXPECT_EQ(fast.last_deepest().b, b.deepest.b) << "step " << step;
        EXPECT_TRUE(std::equal(pen.begin(), pen.end(), b.per_body.begin())) << "step " << step;
      }
    }
    at = next;
  }
  EXPECT_GT(kinds_seen[0], 0);
  EXPECT_GT(kinds_seen[1], 0);
  EXPECT_GT(kinds_seen[2], 0);
  const Metrics a = fast.result(at), b = full.result(at);
  EXPECT_GT(*a.max_penetration, 0.0);
  expect_same(a, b);
}

TEST(MetricsShortcuts, GiveTheFiguresOfAFullScan) {
  for (unsigned seed = 1; seed <= 6; ++seed)
    run_and_compare(false, seed);
}

TEST(MetricsShortcuts, GiveTheFiguresOfAFullScanWithTurnedBoxes) {
  for (unsigned seed = 1; seed <= 3; ++seed)
    run_and_compare(true, seed);
}

// A body thrown to infinity and left there changes nothing step to step, yet a full pass finds its
// displacement NaN every step (inf - inf): told which bodies changed, the recorder finds the same.
TEST(MetricsShortcuts, ABodyHeldAtInfinityIsJudgedAsAFullScanJudgesIt) {
  std::mt19937 rng(9);
  const Scene s = random_scene(rng, false);
  MetricsRecorder fast(s, MetricSelection{}), full(s, MetricSelection{});
  full.scan_every_body();
  BodyState at = initial_state(s);
  const std::size_t thrown = 40;
  for (int step = 1; step <= 12; ++step) {
    BodyState next = at;
    if (step == 3) next.position[thrown].x = HUGE_VAL;
    next.position[50].x += step % 2 == 0 ? 0.01 : 0.0;  // one other body moves now and then
    std::vector<std::uint32_t> changed;
    for (std::size_t i = 0; i < s.bodies.size(); ++i) {
      if (next.position[i].x != at.position[i].x || next.position[i].y != at.position[i].y)
        changed.push_back(static_cast<std::uint32_t>(i));
    }
    fast.observe(at, next, step, true, false, &changed);
    full.observe(at, next, step, true);
    const auto a = fast.step_displacement(), b = full.step_displacement();
    for (std::size_t i = 0; i < a.size(); ++i) {
      EXPECT_TRUE(a[i] == b[i] || (std::isnan(a[i]) && std::isnan(b[i])))
          << "step " << step << " body " << i << ": " << a[i] << " against " << b[i];
    }
    at = next;
  }
  const Metrics a = fast.result(at), b = full.result(at);
  EXPECT_TRUE(std::isnan(*a.efd_total) && std::isnan(*b.efd_total));
  EXPECT_EQ(*a.finite, *b.finite);
  EXPECT_EQ(*a.max_penetration, *b.max_penetration);
}

TEST(MetricsShortcuts, TouchingBoxesDoNotOverlapAndImmovablePairsAreLeftOut) {
  Scene s;
  s.gravity = {0.0, 0.0};
  s.steps = 10;
  s.bodies.push_back({"wall", BodyKind::kStatic, {0.0, 0.0}, {0.5, 0.5}, {}, 0.0, 1.0, {}, {}});
  s.bodies.push_back(
      {"post", BodyKind::kStatic, {0.5, 0.0}, {0.5, 0.5}, {}, 0.0, 1.0, {}, {}});  // into wall
  s.bodies.push_back(
      {"a", BodyKind::kDynamic, {-1.0, 0.0}, {0.5, 0.5}, {}, 1.0, 1.0, {}, {}});  // touches
  s.bodies.push_back(
      {"b", BodyKind::kDynamic, {-1.0, 1.0}, {0.5, 0.5}, {}, 1.0, 1.0, {}, {}});  // touches a
  MetricsRecorder m(s, MetricSelection{});
  BodyState at = initial_state(s);
  for (int step = 1; step <= 3; ++step) {
    m.observe(at, at, step, true);
    EXPECT_EQ(m.last_deepest().depth, 0.0);
    for (const double d : m.step_penetration())
      EXPECT_EQ(d, 0.0);
  }
  BodyState pressed = at;
  pressed.position[3].y = 0.9;  // b sinks 0.1 into a
  m.observe(at, pressed, 4, true);
  EXPECT_NEAR(m.last_deepest().depth, 0.1, 1e-12);
  EXPECT_EQ(m.last_deepest().a, 2u);
  EXPECT_EQ(m.last_deepest().b, 3u);
  m.observe(pressed, pressed, 5, true);  // at rest: still 0.1 deep
  EXPECT_NEAR(m.last_deepest().depth, 0.1, 1e-12);
  EXPECT_EQ(m.last_deepest().step, 5);
}

}  // namespace
}  // namespace chainbench
