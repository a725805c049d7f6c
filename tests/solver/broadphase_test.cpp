// SPDX-License-Identifier: MIT
// The broadphase finds exactly the overlapping pairs a brute-force scan finds, whatever the
// mix of sizes, and still finds a pair after a push moved a body out of its cell.
#include "broadphase.h"
#include "broadphase_helpers.h"
#include "step_context.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>
#include <utility>

namespace chain::detail {
namespace {

class BroadphasePairs : public ::testing::TestWithParam<Mix> {};

INSTANTIATE_TEST_SUITE_P(Solver, BroadphasePairs, ::testing::ValuesIn(kMixes),
                         [](const auto& info) { return std::string(info.param.name); });

TEST_P(BroadphasePairs, MatchBruteForce) {
  const Mix m = GetParam();
  for (std::uint32_t seed = 1; seed <= 3; ++seed) {
    const Bodies b = random_bodies(seed, m.n, m.spread, m.min_half, m.max_half);
    Broadphase bp;
    bp.configure(b);
    bp.build(b);
    Pairs near;
    bp.for_each_near_pair(b, [&](std::uint32_t i, std::uint32_t j) {
      ASSERT_LT(i, j);
      ASSERT_TRUE(near.insert({i, j}).second) << "pair reported twice";
    });
    EXPECT_EQ(near, brute_force(b, -bp.slack())) << "seed " << seed;
  }
}

TEST(Broadphase, QueryAfterAPushFindsBodiesNearTheNewPlace) {
  Bodies b;
  for (int i = 0; i < 50; ++i) {
    BodyDef d;
    d.center = {static_cast<double>(i) * 2.0, 0.0};
    b.append(d, static_cast<std::uint32_t>(i));
  }
  std::vector<std::uint32_t> slot_of_id(b.size());
  const std::vector<chain::detail::Origin> origins(b.size(), chain::detail::Origin{});
  b.canonicalize(slot_of_id, origins);
  Broadphase bp;
  bp.configure(b);
  bp.build(b);
  // Push body 0 (at x = 0) to x = 60.3, onto the body at x = 60.
  const std::uint32_t moved = slot_of_id[0];
  b.pos(0, moved) = 60.3;
  bp.note_move(moved, b.x(moved), b.y(moved));
  std::vector<std::uint32_t> found;
  bp.for_each_overlap(b, moved, 0.0, [&](std::uint32_t j) { found.push_back(j); });
  EXPECT_EQ(found, std::vector<std::uint32_t>{slot_of_id[30]});
  // And a query from the body it now overlaps finds it at its new place.
  found.clear();
  bp.for_each_overlap(b, slot_of_id[30], 0.0, [&](std::uint32_t j) { found.push_back(j); });
  EXPECT_EQ(found, std::vector<std::uint32_t>{moved});
}

// Far moves file bodies again instead of widening every query: after random moves, from tiny to
// far beyond the grid's bounding box, every query still finds exactly the overlaps a brute-force
// scan finds, the near pairs then scanned hold every overlapping pair, and they go on holding it
// while bodies move within the refile distance.
TEST_P(BroadphasePairs, FindEveryOverlapAfterFarMoves) {
  const Mix m = GetParam();
  std::mt19937 rng(99);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Bodies b = random_bodies(7, m.n, m.spread, m.min_half, m.max_half);
  Broadphase bp;
  bp.configure(b);
  bp.build(b);
  auto move = [&](double scale) {
    for (std::uint32_t i = 0; i < b.size(); ++i) {
      if (b.immovable(i) && b.type[i] == BodyType::kStatic) continue;
      if (unit(rng) < 0.5) continue;
      for (int k = 0; k < 2; ++k)
        b.pos(k, i) += (unit(rng) - 0.5) * scale;
      bp.note_move(i, b.x(i), b.y(i));
    }
  };
  auto check_queries = [&] {
    const Pairs truth = brute_force(b, 0.0);
    Pairs found;
    for (std::uint32_t i = 0; i < b.size(); ++i) {
      bp.for_each_overlap(b, i, 0.0, [&](std::uint32_t j) {
        if (!(b.immovable(i) && b.immovable(j))) found.insert({std::min(i, j), std::max(i, j)});
      });
    }
    EXPECT_EQ(found, truth);
  };
  move(4.0 * m.spread);  // most moves far: filed again, some beyond the grid
  check_queries();
  Pairs near;
  bp.for_each_near_pair(b, [&](std::uint32_t i, std::uint32_t j) {
    ASSERT_LT(i, j);
    ASSERT_TRUE(near.insert({i, j}).second) << "pair reported twice";
  });
  for (const auto& p : brute_force(b, 0.0))
    EXPECT_TRUE(near.count(p)) << p.first << " " << p.second;
  // Moves within the refile distance keep the near pairs whole.
  for (int round = 0; round < 3; ++round) {
    for (std::uint32_t i = 0; i < b.size(); ++i) {
      if (b.type[i] == BodyType::kStatic) continue;
      for (int k = 0; k < 2; ++k) {
        const double d = (unit(rng) - 0.5) * bp.refile_distance() / 2.0;
        b.pos(k, i) += d;
      }
      bp.note_move(i, b.x(i), b.y(i));
    }
    if (!bp.near_pairs_hold()) continue;  // some body went past its refile distance: no promise
    for (const auto& p : brute_force(b, 0.0))
      EXPECT_TRUE(near.count(p)) << "round " << round << ": " << p.first << " " << p.second;
  }
  check_queries();
}

// Bodies destroyed in place and bodies created into their slots (World's churn without a
// re-sort): after Bodies::kill and remove() of a third of the dynamic bodies, and new bodies of
// the sizes the levels hold put into half of those slots at random places and insert()ed, every
// query finds exactly the overlaps a brute-force scan of the bodies in the world finds, a new body
// is stale, and the near pairs scanned before, with the stale bodies' overlaps, give every
// overlapping pair of a body that is not (as ChainState::gather_overlaps takes them).
TEST_P(BroadphasePairs, EmptiedAndRefilledSlotsAreFoundWhereTheyAre) {
  const Mix m = GetParam();
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Bodies b = random_bodies(11, m.n, m.spread, m.min_half, m.max_half);
  Broadphase bp;
  bp.configure(b);
  bp.build(b);
  const std::vector<std::vector<std::uint32_t>> near = near_lists(bp, b);
  std::vector<std::uint32_t> emptied;
  for (std::uint32_t i = 0; i < b.dynamic_end; ++i) {
    if (unit(rng) < 1.0 / 3.0) {
      b.kill(i);
      bp.remove(i);
      emptied.push_back(i);
    }
  }
  std::vector<std::uint32_t> refilled;
  for (std::size_t k = 0; k < emptied.size(); k += 2) {
    const std::uint32_t slot = emptied[k];
    // The size of a living body, so that it fits a level; placed anywhere in the scene.
    std::uint32_t like = static_cast<std::uint32_t>(unit(rng) * b.dynamic_end);
    while (b.dead(like))
      like = (like + 1) % b.dynamic_end;
    b.box[slot].half[0] = b.hx(like), b.box[slot].half[1] = b.hy(like);
    b.box[slot].center[0] = (unit(rng) - 0.5) * 2.0 * m.spread;
    b.box[slot].center[1] = (unit(rng) - 0.5) * 2.0 * m.spread;
    b.id[slot] = 100000 + slot;
    ASSERT_TRUE(bp.fits(std::max(b.hx(slot), b.hy(slot))));
    bp.insert(b, slot);
    EXPECT_TRUE(bp.stale(slot));
    refilled.push_back(slot);
  }
  ASSERT_FALSE(refilled.empty());
  const double tol = 1e-9;
  // The brute force over the bodies in the world: an emptied slot's NaN centre is left out here,
  // as its min/max form would not leave it out by itself.
  Pairs truth = brute_force(b, tol);
  std::erase_if(truth, [&](const auto& pair) { return b.dead(pair.first) || b.dead(pair.second); });
  const std::vector<std::set<std::uint32_t>> overlaps = per_body(truth, b.size());
  for (std::uint32_t i = 0; i < b.size(); ++i) {
    if (b.dead(i)) continue;
    std::set<std::uint32_t> found;
    bp.for_each_overlap(b, i, tol, [&](std::uint32_t j) {
      EXPECT_FALSE(b.dead(j)) << "an emptied slot was found";
      found.insert(j);
    });
    std::set<std::uint32_t> expected = overlaps[i];
    if (b.immovable(i)) {
      std::erase_if(expected, [&](std::uint32_t j) { return b.immovable(j); });
      std::erase_if(found, [&](std::uint32_t j) { return b.immovable(j); });
    }
    EXPECT_EQ(found, expected) << "body " << i;
    if (bp.stale(i)) continue;
    std::set<std::uint32_t> gathered;
    for (const std::uint32_t j : near[i]) {
      if (!bp.stale(j) && overlaps[i].count(j)) gathered.insert(j);
    }
    bp.for_each_stale_overlap(b, i, tol, [&](std::uint32_t j) { gathered.insert(j); });
    EXPECT_EQ(gathered, expected) << "body " << i << ", from its near pairs";
  }
}

// A few bodies filed again far from where they were (a chain's far pushes), the others moved
// within the refile distance: every body that no body filed again came near (near_stale() false)
// overlaps exactly the bodies of its near list it overlaps now, none of them stale, so its query
// may take its near list whole (ChainState::gather_overlaps) while others are stale.
TEST_P(BroadphasePairs, ABodyNoRefiledBodyCameNearHasItsOverlapsInItsNearList) {
  const Mix m = GetParam();
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Bodies b = random_bodies(13, m.n, m.spread, m.min_half, m.max_half);
  Broadphase bp;
  bp.configure(b);
  bp.build(b);
  const std::vector<std::vector<std::uint32_t>> near = near_lists(bp, b);
  for (std::uint32_t i = 0; i < b.dynamic_end; ++i) {
    const bool far = unit(rng) < 0.05;
    for (int k = 0; k < 2; ++k) {
      b.pos(k, i) += far ? (unit(rng) - 0.5) * m.spread : (unit(rng) - 0.5) * bp.refile_distance();
    }
    bp.note_move(i, b.x(i), b.y(i));
  }
  ASSERT_FALSE(bp.near_pairs_hold());
  const double tol = 1e-9;
  const Pairs truth = brute_force(b, tol);
  const std::vector<std::set<std::uint32_t>> overlaps = per_body(truth, b.size());
  std::size_t whole = 0, stale_near = 0;
  for (std::uint32_t i = 0; i < b.size(); ++i) {
    if (bp.near_stale(i)) {
      ++stale_near;
      continue;
    }
    ++whole;
    EXPECT_FALSE(bp.stale(i));
    std::set<std::uint32_t> found;
    for (const std::uint32_t j : near[i]) {
      if (overlapping(b, i, j, tol)) {
        EXPECT_FALSE(bp.stale(j)) << "body " << i << " overlaps " << j << ", filed again near it";
        found.insert(j);
      }
    }
    std::set<std::uint32_t> expected = overlaps[i];
    if (b.immovable(i)) std::erase_if(expected, [&](std::uint32_t j) { return b.immovable(j); });
    EXPECT_EQ(found, expected) << "body " << i;
  }
  // Where bodies span a good part of the scene (TinyAndHuge), every body is near a stale one.
  if (4.0 * m.max_half < m.spread) {
    EXPECT_GT(whole, 0u);
  }
  EXPECT_GT(stale_near, 0u);
}

// A size level every body of which has left (here: emptied slots, whose NaN centres give no
// bounds) still builds, and every query still finds what a brute-force scan finds. Kept from the
// world fuzzer's find: the empty level's bounds ran from +max to -max, and its cell count from
// -inf.
TEST(Broadphase, ALevelWhoseBodiesAllLeftStillBuildsAndAnswers) {
  for (const bool kill_large : {true, false}) {
    Bodies b;
    for (std::uint32_t i = 0; i < 12; ++i) {
      BodyDef d;
      d.type = BodyType::kDynamic;
      const bool large = i % 3 == 0;
      d.half_extents = large ? Vec2{2.0, 2.0} : Vec2{0.2, 0.2};
      d.center = {static_cast<double>(i) * 0.35, large ? 3.0 : 0.2};
      b.append(d, i);
    }
    BodyDef ground;
    ground.type = BodyType::kStatic;
    ground.center = {0.0, -1.0};
    ground.half_extents = {20.0, 1.0};
    b.append(ground, 12);
    std::vector<std::uint32_t> slot_of_id(b.size());
    b.canonicalize(slot_of_id, std::vector<chain::detail::Origin>(b.size()));
    Broadphase bp;
    bp.configure(b);
    bp.build(b);
    for (std::uint32_t i = 0; i < b.dynamic_end; ++i) {
      if ((b.hx(i) > 1.0) == kill_large) b.kill(i), bp.remove(i);
    }
    bp.build(b);
    const double tol = 1e-9;
    Pairs truth = brute_force(b, tol);
    std::erase_if(truth,
                  [&](const auto& pair) { return b.dead(pair.first) || b.dead(pair.second); });
    std::vector<std::set<std::uint32_t>> overlaps(b.size());
    for (const auto& [p, q] : truth)
      overlaps[p].insert(q), overlaps[q].insert(p);
    std::size_t found_any = 0;
    for (std::uint32_t i = 0; i < b.dynamic_end; ++i) {
      if (b.dead(i)) continue;
      std::set<std::uint32_t> found;
      bp.for_each_overlap(b, i, tol, [&](std::uint32_t j) { found.insert(j); });
      EXPECT_EQ(found, overlaps[i]) << "body " << i << (kill_large ? ", large killed" : "");
      found_any += found.size();
    }
    EXPECT_GT(found_any, 0u) << "the scene is built to overlap: neighbours and the ground";
  }
}

}  // namespace
}  // namespace chain::detail
