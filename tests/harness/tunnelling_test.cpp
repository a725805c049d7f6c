// SPDX-License-Identifier: MIT
// Tunnelling judged by where each centre goes in and comes out: the property that a body whose
// centre runs into two touching blocks along their shared face and comes out at the far end
// passed through them, whatever the sizes, the speed and the rounding of the scene's decimals.
#include "judge/tunnelling.h"

#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

namespace chainbench {
namespace {

BodyState state(std::vector<Vec2d> pos) {
  BodyState s(pos.size());
  s.position = std::move(pos);
  return s;
}

// Two static blocks stacked face to face (a below, b on it) and a bullet, as a scene file would
// give them: decimals of two places, so that the seam the bullet runs along is where rounding
// puts it.
struct Seam {
  Scene scene;
  double seam = 0.0;               // the y of the shared face, as the file writes it
  double left = 0.0, right = 0.0;  // bullet x beyond either end of the blocks
};

Seam stacked_blocks(std::mt19937& rng) {
  auto hundredths = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
  const int ax = hundredths(-500, 500), ay = hundredths(-500, 500);
  const int wa = hundredths(5, 300), ha = hundredths(5, 300);
  const int wb = hundredths(5, 300), hb = hundredths(5, 300);
  const int bw = hundredths(1, 100), bh = hundredths(1, 100);
  // The double nearest the decimal v / 100, as parsing the file's text gives it.
  auto d = [](int v) { return v / 100.0; };
  Seam s;
  s.scene.gravity = {0.0, 0.0};
  s.scene.dt = 1.0 / 60.0;
  s.scene.steps = 100;
  s.seam = d(ay + ha);
  const double reach = d(std::max(wa, wb) + bw + 10);
  s.left = d(ax) - reach;
  s.right = d(ax) + reach;
  s.scene.bodies.push_back(
      {"bullet", BodyKind::kDynamic, {s.left, s.seam}, {d(bw), d(bh)}, {}, 1.0, 1.0, {}, {}});
  s.scene.bodies.push_back(
      {"a", BodyKind::kStatic, {d(ax), d(ay)}, {d(wa), d(ha)}, {}, 1.0, 1.0, {}, {}});
  s.scene.bodies.push_back(
      {"b", BodyKind::kStatic, {d(ax), d(ay + ha + hb)}, {d(wb), d(hb)}, {}, 1.0, 1.0, {}, {}});
  return s;
}

// Moves the bullet along `xs` at height y, judging both of its pairs each step.
TunnelWatch slide(const Seam& s, const std::vector<double>& xs, double y) {
  TunnelWatch w(s.scene);
  const Vec2d a = s.scene.bodies[1].center, b = s.scene.bodies[2].center;
  for (std::size_t k = 1; k < xs.size(); ++k) {
    const BodyState before = state({{xs[k - 1], y}, a, b}), after = state({{xs[k], y}, a, b});
    w.check(before, after, 0, 1, static_cast<int>(k));
    w.check(before, after, 0, 2, static_cast<int>(k));
    w.end_step();
  }
  return w;
}

std::vector<double> path(double from, double to, int steps) {
  std::vector<double> xs;
  for (int k = 0; k <= steps; ++k)
    xs.push_back(from + (to - from) * k / steps);
  return xs;
}

TEST(Tunnelling, ABulletAlongTheSeamOfTwoStackedBlocksAndOutAtTheFarEndPassedThrough) {
  std::mt19937 rng(2026);
  for (int c = 0; c < 2000; ++c) {
    const Seam s = stacked_blocks(rng);
    const int steps = std::uniform_int_distribution<int>(1, 60)(rng);
    SCOPED_TRACE("case " + std::to_string(c) + ", " + std::to_string(steps) + " steps");
    const TunnelWatch through = slide(s, path(s.left, s.right, steps), s.seam);
    ASSERT_TRUE(through.first().has_value());
    EXPECT_EQ(through.first()->body, 0u);
    // Its centre ran along a face of each block: through both, each pair once a visit.
    EXPECT_EQ(through.count(), 2u);
    // In along the seam and back out at the end it came in by: not through.
    std::vector<double> back = path(s.left, 0.5 * (s.left + s.right), steps);
    const std::vector<double> out = path(0.5 * (s.left + s.right), s.left, steps);
    back.insert(back.end(), out.begin() + 1, out.end());
    EXPECT_EQ(slide(s, back, s.seam).count(), 0u);
    // Clear above the upper block: nothing.
    const double above = s.scene.bodies[2].center.y + s.scene.bodies[2].half_extents.y +
                         s.scene.bodies[0].half_extents.y + 0.01;
    EXPECT_EQ(slide(s, path(s.left, s.right, steps), above).count(), 0u);
  }
}

// A centre that goes into a block by one face and out by a side face passed through it, as one
// that goes out by the opposite face does: pressed into the top of a slab until its centre is
// inside, then carried out through its end.
TEST(Tunnelling, OutThroughAnyFaceButTheEntryFaceIsThrough) {
  Scene s;
  s.gravity = {0.0, 0.0};
  s.bodies.push_back({"box", BodyKind::kDynamic, {0, 2}, {0.1, 0.1}, {}, 1.0, 1.0, {}, {}});
  s.bodies.push_back({"slab", BodyKind::kStatic, {0, 0}, {2.0, 0.5}, {}, 1.0, 1.0, {}, {}});
  auto count = [&](std::vector<Vec2d> path) {
    TunnelWatch w(s);
    for (std::size_t k = 1; k < path.size(); ++k) {
      w.check(state({path[k - 1], {0, 0}}), state({path[k], {0, 0}}), 0, 1, static_cast<int>(k));
      w.end_step();
    }
    return w.count();
  };
  EXPECT_EQ(count({{0, 0.65}, {0, 0.3}, {1.0, 0.3}, {2.5, 0.3}}), 1u);  // in on top, out the end
  EXPECT_EQ(count({{0, 0.65}, {0, 0.3}, {1.0, 0.3}, {1.0, 0.7}}), 0u);  // back out on top
  EXPECT_EQ(count({{0, 0.65}, {0, 0.55}, {2.5, 0.55}}), 0u);  // 0.05 m in, centre never inside
}

}  // namespace
}  // namespace chainbench
