// SPDX-License-Identifier: MIT
// A PairCache lists the pairs a grid built afresh every step would find: on a field of boxes that
// drift at steady speeds (the cache keeps its list), start and stop, and now and then jump far or
// turn non-finite, or are thrown so far that their boxes are giants (it refits those bodies, or
// files all again), whether every body is measured or only the moved ones.
#include "index/pair_cache.h"

#include "judge/metrics.h"

#include <gtest/gtest.h>

#include <algorithm>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace chainbench {
namespace {

using Pairs = std::vector<std::pair<std::size_t, std::size_t>>;

// Boxes on a lattice whose neighbours touch, a static floor under them and a kinematic block.
Scene field() {
  Scene s;
  s.dt = 1.0 / 60.0;
  s.steps = 1000;
  s.bodies.push_back({"floor", BodyKind::kStatic, {0.0, -1.0}, {400.0, 1.0}, {}, 0.0, 1.0, {}, {}});
  s.bodies.push_back(
      {"block", BodyKind::kKinematic, {-3.0, 3.0}, {1.0, 0.5}, {}, 0.0, 1.0, {}, {}});
  for (int row = 0; row < 10; ++row) {
    for (int col = 0; col < 30; ++col) {
      SceneBody box;
      box.name = "box";
      box.center = {-15.0 + col * 1.0, 0.5 + row * 1.0};
      s.bodies.push_back(box);
    }
  }
  return s;
}

Pairs scanned(const Scene& s, const BodyState& before, const BodyState& after) {
  PairScan scan(s);
  scan.build(before, after);
  Pairs out;
  scan.for_each_pair([&](std::size_t i, std::size_t j) { out.emplace_back(i, j); });
  std::sort(out.begin(), out.end());
  return out;
}

void drift_jump_and_stop(unsigned seed) {
  SCOPED_TRACE("seed " + std::to_string(seed));
  const Scene s = field();
  const std::size_t n = s.bodies.size();
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0), pace(-0.03, 0.03);
  std::vector<Vec2d> drift(n);
  for (std::size_t i = 1; i < n; ++i)
    drift[i] = {pace(rng), pace(rng)};
  PairCache cache(s);
  BodyState at = initial_state(s);
  std::vector<std::uint32_t> moved;
  std::vector<std::uint8_t> active(n, 0);
  constexpr int kSteps = 200;
  int partial_steps = 0;
  for (int step = 1; step <= kSteps; ++step) {
    BodyState next = at;
    moved.clear();
    // Half the steps move every body but the floor; the others a few, as the recorder sees them.
    const bool all = step % 2 == 0;
    for (std::size_t i = 1; i < n; ++i) {
      if (!all && unit(rng) > 0.05) continue;
      next.position[i].x += drift[i].x;
      next.position[i].y += drift[i].y;
      if (unit(rng) < 0.0005) next.position[i].x += 3.0;     // far, through its neighbours
      if (unit(rng) < 0.0002) next.position[i].y += 4000.0;  // thrown: a giant swept box
      if (unit(rng) < 0.0003) next.position[i].y = std::numeric_limits<double>::quiet_NaN();
      if (std::isnan(at.position[i].y) && unit(rng) < 0.5) next.position[i].y = 2.0;
      moved.push_back(static_cast<std::uint32_t>(i));
    }
    const Pairs want = scanned(s, at, next);
    Pairs got;
    auto collect = [&](std::size_t i, std::size_t j) { got.emplace_back(i, j); };
    if (all) {
      cache.for_each_pair(at, next, collect);
      std::sort(got.begin(), got.end());
      ASSERT_EQ(got, want) << "step " << step;
    } else {
      ++partial_steps;
      for (const std::uint32_t i : moved)
        active[i] = 1;
      cache.for_each_pair_of(at, next, moved, active, collect);
      Pairs with_moved;
      for (const auto& [i, j] : want) {
        if (active[i] || active[j]) with_moved.emplace_back(i, j);
      }
      for (const std::uint32_t i : moved)
        active[i] = 0;
      std::sort(got.begin(), got.end());
      ASSERT_EQ(got, with_moved) << "step " << step;
    }
    // Giants' pairs are tested, never held: the lists stay near a few pairs per body.
    ASSERT_LT(cache.listed(), 6 * n) << "step " << step;
    at = next;
  }
  EXPECT_GT(partial_steps, 0);
  // Drifting at up to 0.03 m a step in cells of 1 m, the list serves several steps; single
  // bodies leaving their fat boxes (the jumps, the first steps of a drift) are refitted one by
  // one, and when many have drifted out at once every body is filed again.
  EXPECT_LT(cache.filings(), static_cast<std::uint64_t>(kSteps / 10));
  EXPECT_GT(cache.filings(), 3u);
  EXPECT_GT(cache.refits(), 50u);
}

TEST(PairCache, ListsThePairsOfAFreshScanWhileBodiesDriftJumpAndStop) {
  for (unsigned seed = 1; seed <= 8; ++seed)
    drift_jump_and_stop(seed);
}

}  // namespace
}  // namespace chainbench
