// SPDX-License-Identifier: MIT
// Bodies filed at their boxes stretched along their way (Broadphase::build with a step): while each
// body keeps within its filed box grown by the refile distance, the near pairs hold every
// overlapping pair, every query finds what a brute-force scan finds, and a body that goes on at
// the velocity it was filed with is not filed again for kAheadSteps steps.
#include "broadphase.h"
#include "broadphase_helpers.h"
#include "step_context.h"

#include <chain/world.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <set>
#include <vector>

namespace chain::detail {
namespace {

constexpr double kDt = 1.0 / 60.0;
constexpr Vec2 kGravity{0.0, -10.0};

class BroadphaseStretch : public ::testing::TestWithParam<Mix> {};

INSTANTIATE_TEST_SUITE_P(Solver, BroadphaseStretch, ::testing::ValuesIn(kMixes),
                         [](const auto& info) { return std::string(info.param.name); });

// Every movable body a velocity before this step's gravity (`way`, m/s), each axis on its own: a
// third at rest, the others taking it from 2 refile distances to `top` (m) in kAheadSteps steps,
// either way; without `across`, along y only (rain, a lift). The bodies' velocities are set as
// integration leaves them: with this step's gravity on the dynamic ones.
std::vector<Point> give_velocities(Bodies& b, double refile, double top, std::mt19937& rng,
                                   bool across = true) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double ahead = Broadphase::kAheadSteps * kDt;
  std::vector<Point> way(b.size(), Point{0.0, 0.0});
  for (std::uint32_t i = 0; i < b.movable_end; ++i) {
    double* const go = &way[i].x;
    for (int axis = across ? 0 : 1; axis < 2; ++axis) {
      if (unit(rng) < 1.0 / 3.0) continue;
      const double far = 2.0 * refile * (1.0 + 1e-6) + unit(rng) * (top - 2.0 * refile);
      go[axis] = (unit(rng) < 0.5 ? -far : far) / ahead;
    }
    b.vx[i] = way[i].x;
    b.vy[i] = way[i].y + (i < b.dynamic_end ? kGravity.y * kDt : 0.0);
  }
  return way;
}

// kAheadSteps steps of every movable body going at its way, each step's move off by up to an
// eighth of the refile distance, and one body in 40 thrown far each step: after every step the
// near pairs hold every overlapping pair of bodies not filed again, bodies no refiled body came
// near find all their overlaps in their near lists, and every query finds exactly the overlaps.
void check_going_their_way(const Mix& m, bool across);

TEST_P(BroadphaseStretch, NearPairsAndQueriesHoldWhileBodiesGoTheirWay) {
  for (const bool across : {true, false}) {
    SCOPED_TRACE(across ? "along both axes" : "along y only");
    check_going_their_way(GetParam(), across);
  }
}

void check_going_their_way(const Mix& m, bool across) {
  std::mt19937 rng(41);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Bodies b = random_bodies(17, m.n, m.spread, m.min_half, m.max_half);
  Broadphase bp;
  bp.configure(b);
  const double r = bp.refile_distance();
  // Some ways longer than twice the largest body: stretches cut at their level's largest.
  const std::vector<Point> way = give_velocities(b, r, 4.0 * m.max_half, rng, across);
  bp.build(b, kDt, kGravity);
  const std::vector<std::vector<std::uint32_t>> near = near_lists(bp, b);
  const std::vector<std::set<std::uint32_t>> near_sets = [&] {
    std::vector<std::set<std::uint32_t>> out(b.size());
    for (std::uint32_t i = 0; i < b.size(); ++i)
      out[i].insert(near[i].begin(), near[i].end());
    return out;
  }();
  // Right after the scan, the near pairs hold every pair closer than the slack.
  for (const auto& [i, j] : brute_force(b, -bp.slack()))
    ASSERT_TRUE(near_sets[i].count(j)) << i << " " << j;

  const double tol = 1e-9;
  std::size_t thrown = 0;
  for (int step = 0; step < static_cast<int>(Broadphase::kAheadSteps); ++step) {
    for (std::uint32_t i = 0; i < b.movable_end; ++i) {
      const bool far = unit(rng) < 0.025;
      thrown += far;
      for (int k = 0; k < 2; ++k) {
        const double go = k == 0 ? way[i].x : way[i].y;
        b.pos(k, i) += far ? (unit(rng) - 0.5) * m.spread : go * kDt + (unit(rng) - 0.5) * r / 8.0;
      }
      bp.note_move(i, b.x(i), b.y(i));
    }
    const Pairs truth = brute_force(b, tol);
    const std::vector<std::set<std::uint32_t>> overlaps = per_body(truth, b.size());
    for (const auto& [i, j] : truth) {
      if (bp.stale(i) || bp.stale(j)) continue;
      EXPECT_TRUE(near_sets[i].count(j)) << "step " << step << ": " << i << " " << j;
    }
    for (std::uint32_t i = 0; i < b.size(); ++i) {
      std::set<std::uint32_t> found;
      bp.for_each_overlap(b, i, tol, [&](std::uint32_t j) { found.insert(j); });
      std::set<std::uint32_t> expected = overlaps[i];
      if (b.immovable(i)) std::erase_if(expected, [&](std::uint32_t j) { return b.immovable(j); });
      std::set<std::uint32_t> queried = found;
      if (b.immovable(i)) std::erase_if(queried, [&](std::uint32_t j) { return b.immovable(j); });
      EXPECT_EQ(queried, expected) << "step " << step << ", body " << i;
      if (bp.near_stale(i)) continue;
      std::set<std::uint32_t> listed;
      for (const std::uint32_t j : near[i]) {
        if (overlapping(b, i, j, tol)) listed.insert(j);
      }
      EXPECT_EQ(listed, expected) << "step " << step << ", body " << i << " (its near list)";
    }
  }
  EXPECT_GT(thrown, 0u);
}

// A body that goes on at the velocity it was filed with, off by no more than an eighth of the
// refile distance a step, stays where it is filed for kAheadSteps steps when its way in that time
// is no longer than twice the smallest body or 4 refile distances (so within any level's cut on a
// stretch). Filed at its box, as
// before stretches, every one whose way is longer than the refile distance would have been filed
// again.
TEST_P(BroadphaseStretch, ABodyGoingItsWayIsNotFiledAgainForTheStepsAhead) {
  const Mix m = GetParam();
  std::mt19937 rng(43);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Bodies b = random_bodies(19, m.n, m.spread, m.min_half, m.max_half);
  Broadphase bp;
  bp.configure(b);
  const double r = bp.refile_distance();
  // Up to twice the smallest body or 4 refile distances (a sixteenth of the finest level's
  // largest half extent): within every level's largest half extent, the cut on a stretch.
  const std::vector<Point> way = give_velocities(b, r, std::max(2.0 * m.min_half, 4.0 * r), rng);
  bp.build(b, kDt, kGravity);
  std::size_t going = 0;
  for (int step = 0; step < static_cast<int>(Broadphase::kAheadSteps); ++step) {
    for (std::uint32_t i = 0; i < b.movable_end; ++i) {
      for (int k = 0; k < 2; ++k) {
        const double go = k == 0 ? way[i].x : way[i].y;
        b.pos(k, i) += go * kDt + (unit(rng) - 0.5) * r / 4.0;  // off by up to r / 8
      }
      bp.note_move(i, b.x(i), b.y(i));
    }
  }
  for (std::uint32_t i = 0; i < b.movable_end; ++i) {
    EXPECT_FALSE(bp.stale(i)) << "body " << i;
    going += std::max(std::abs(way[i].x), std::abs(way[i].y)) * Broadphase::kAheadSteps * kDt > r;
  }
  EXPECT_TRUE(bp.near_pairs_hold());
  EXPECT_GT(going, b.movable_end / 3);  // most went further than their refile distance
}

// Filed with no step (the 2014 variant's grid, and the near pairs before any motion is known),
// the near pairs are exactly the pairs closer than the slack, as without stretches.
TEST_P(BroadphaseStretch, WithoutAStepEveryBodyIsFiledAtItsBox) {
  const Mix m = GetParam();
  std::mt19937 rng(47);
  Bodies b = random_bodies(23, m.n, m.spread, m.min_half, m.max_half);
  Broadphase bp;
  bp.configure(b);
  give_velocities(b, bp.refile_distance(), 4.0 * m.max_half, rng);
  bp.build(b);
  Pairs near;
  bp.for_each_near_pair(b, [&](std::uint32_t i, std::uint32_t j) { near.insert({i, j}); });
  EXPECT_EQ(near, brute_force(b, -bp.slack()));
}

// The near-pair scan gives every pair of filed boxes (each stretched along its way, or not) that
// come within the slack, once, and no other: against brute force over the filed boxes, on 16
// layouts of the mix going every way and along y only. Stretched and unstretched bodies are found
// by different sides of the scan (broadphase_scans.h); a pair missed or found twice shows here.
TEST_P(BroadphaseStretch, TheNearPairsAreExactlyThoseOfTheFiledBoxes) {
  const Mix m = GetParam();
  std::size_t pairs = 0, stretched_pairs = 0;
  for (std::uint32_t seed = 1; seed <= 8; ++seed) {
    for (const bool across : {true, false}) {
      std::mt19937 rng(seed * 7 + (across ? 1 : 0));
      Bodies b = random_bodies(seed, m.n, m.spread, m.min_half, m.max_half);
      Broadphase bp;
      bp.configure(b);
      give_velocities(b, bp.refile_distance(), (seed % 3 + 1) * 2.0 * m.max_half, rng, across);
      bp.build(b, kDt, kGravity);
      std::map<std::pair<std::uint32_t, std::uint32_t>, int> found;
      bp.for_each_near_pair(b, [&](std::uint32_t i, std::uint32_t j) { ++found[{i, j}]; });
      const Point* const at = bp.filed_at();
      const Broadphase::Stretch* const by = bp.stretched_by();
      std::map<std::pair<std::uint32_t, std::uint32_t>, int> expected;
      for (std::uint32_t i = 0; i < b.size(); ++i) {
        for (std::uint32_t j = i + 1; j < b.size(); ++j) {
          if (b.immovable(i) && b.immovable(j)) continue;
          const double hx = (b.hx(i) + by[i].x) + (b.hx(j) + by[j].x);
          const double hy = (b.hy(i) + by[i].y) + (b.hy(j) + by[j].y);
          if (hx - std::abs(at[i].x - at[j].x) > -bp.slack() &&
              hy - std::abs(at[i].y - at[j].y) > -bp.slack()) {
            expected[{i, j}] = 1;
            ++pairs;
            if (by[i].x != 0.0f || by[i].y != 0.0f || by[j].x != 0.0f || by[j].y != 0.0f)
              ++stretched_pairs;
          }
        }
      }
      ASSERT_EQ(found, expected) << "seed " << seed << (across ? ", every way" : ", along y");
    }
  }
  // Not vacuous where bodies meet at all (SparseFarApart's seldom do): most pairs have a
  // stretched body.
  if (pairs > 100) {
    EXPECT_GT(2 * stretched_pairs, pairs);
  }
}

// A stretch cut at its level's largest half extent is no larger than that, to the bit: the
// near-pair scan looks two cells around a stretched entry, which holds every pair only while the
// stretch passes that half extent by less than the slack, and the slack is a quarter of the
// finest level's largest half extent. A float stretch rounded to nearest passed it by up to 2^-24
// of it: in a level 2^21 times coarser than the finest (boulders beside pebbles) that missed
// overlapping pairs. 1000.000031 is such a half extent: its nearest float is 1000.000061.
TEST(BroadphaseStretchCut, ACutStretchIsNoLargerThanItsLevelsLargestBody) {
  constexpr double kLargest = 1000.000031;
  ASSERT_GT(static_cast<double>(static_cast<float>(kLargest)), kLargest);
  std::mt19937 rng(53);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Bodies b;
  std::uint32_t id = 0;
  for (int i = 0; i < 60; ++i) {  // the finest level: its slack is 2.5e-5
    BodyDef d;
    d.center = {1.0 * i, -5000.0};
    d.half_extents = {1e-4, 1e-4};
    b.append(d, id++);
  }
  for (int i = 0; i < 20; ++i) {  // the coarsest, the largest of it kLargest
    BodyDef d;
    const double half = i == 0 ? kLargest : 600.0 + 400.0 * unit(rng);
    d.center = {3000.0 * i, 0.0};
    d.half_extents = {half, half};
    d.velocity = {(unit(rng) < 0.5 ? -1e5 : 1e5), (unit(rng) < 0.5 ? -1e5 : 1e5)};
    d.gravity_scale = 0.0;
    b.append(d, id++);
  }
  std::vector<std::uint32_t> slot_of_id(b.size());
  const std::vector<Origin> origins(b.size(), Origin{});
  b.canonicalize(slot_of_id, origins);
  Broadphase bp;
  bp.configure(b);
  ASSERT_EQ(bp.level_count(), 2u);
  bp.build(b, kDt, kGravity);
  for (std::uint32_t i = 0; i < b.size(); ++i) {
    if (b.hx(i) < 1.0) continue;
    const Broadphase::Stretch s = bp.stretched_by()[i];
    EXPECT_LE(static_cast<double>(s.x), kLargest) << "body " << i;
    EXPECT_LE(static_cast<double>(s.y), kLargest) << "body " << i;
    EXPECT_GT(static_cast<double>(s.x), 0.99 * kLargest) << "body " << i << ": cut, not dropped";
  }
}

}  // namespace
}  // namespace chain::detail
