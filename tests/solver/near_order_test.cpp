// SPDX-License-Identifier: MIT
// A step's result does not depend on the broadphase's history: when the near pairs were last
// scanned, which bodies were filed again since, and what the near lists hold beyond the bodies
// that overlap. Chains meet a body's overlaps in slot order and the contacts come ordered by
// their bodies' slots however they were found (chain_state.cpp, chain_contacts.cpp). Each world
// below is stepped twice in lockstep, once as it comes and once scanning its near pairs anew
// (grid rebuilt) every step, and every body must agree to the bit after every step.
#include "broadphase_helpers.h"
#include "chain_state.h"
#include "world_access.h"
#include "world_helpers.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <functional>
#include <random>
#include <string>
#include <vector>

namespace chain::testing {
namespace {

struct Case {
  std::string name;
  std::function<void(World&)> build;
  int steps;
  // Calls made before a step (k counts from 0), the same in both worlds.
  std::function<void(World&, int)> before_step = [](World&, int) {};
};

// A pusher at 2 m/s into a row of boxes on a floor: one chain through the whole row a step.
void push_row(World& w) {
  add_floor(w, 200.0);
  w.create_body(kinematic_box(-1.0, 0.5, 0.5, 0.5, {2.0, 0.0}));
  for (int i = 0; i < 150; ++i)
    w.create_body(dynamic_box(0.0 + i, 0.5));
}

// Columns of mixed boxes falling onto shelves and a floor, landing at different steps.
void rain(World& w) {
  add_floor(w, 60.0);
  for (int s = 0; s < 3; ++s)
    w.create_body(static_box(-20.0 + 20.0 * s, 4.0 + 3.0 * s, 4.0, 0.01));
  std::mt19937 next(12345u);
  for (int c = 0; c < 40; ++c) {
    double y = 8.0 + (next() % 100) * 0.05;
    for (int k = 0; k < 6; ++k) {
      const double half = 0.15 + (next() % 100) * 0.004;
      w.create_body(dynamic_box(-28.0 + 1.4 * c, y, half));
      y += 2.0 * half + 0.3 + (next() % 10) * 0.05;
    }
  }
}

// Stacks struck from the side by boxes thrown at 40 m/s, one every 10 steps.
void smash(World& w) {
  add_floor(w, 100.0);
  for (int s = 0; s < 6; ++s) {
    for (int k = 0; k < 8; ++k)
      w.create_body(dynamic_box(10.0 * s, 0.5 + k));
  }
  for (int p = 0; p < 6; ++p) {
    BodyDef d = dynamic_box(-30.0 - 3.0 * p, 0.5 + p, 0.4, 3.0);
    d.velocity = {40.0, 0.0};
    w.create_body(d);
  }
}

// Blades carrying crates along a floor, and crates in their way.
void bulldozer(World& w) {
  add_floor(w, 200.0);
  for (int lane = 0; lane < 3; ++lane) {
    const double y = 12.0 * lane;
    if (lane > 0) w.create_body(static_box(40.0, y - 1.0, 60.0, 1.0));
    w.create_body(kinematic_box(-2.0, y + 1.0, 0.5, 1.0, {3.0, 0.0}));
    for (int k = 0; k < 30; ++k)
      w.create_body(dynamic_box(1.0 + 1.7 * k, y + 0.5, 0.45));
  }
}

// `count` boxes of half extents min_half to max_half poured into a bin whose inner half width is
// `half_width`, in rows as wide as the bin holds, each box a little off its place.
void pour(World& w, double half_width, int count, double min_half, double max_half,
          std::uint32_t seed) {
  add_floor(w, half_width + 10.0);
  w.create_body(static_box(-half_width - 1.0, 40.0, 1.0, 40.0));
  w.create_body(static_box(half_width + 1.0, 40.0, 1.0, 40.0));
  std::mt19937 next(seed);
  const double pitch = 2.0 * max_half + 0.1;
  const int columns = std::max(1, static_cast<int>(2.0 * half_width / pitch));
  for (int i = 0; i < count; ++i) {
    const double half = min_half + (max_half - min_half) * (next() % 1000) * 1e-3;
    const double x = -half_width + 0.5 * pitch + (i % columns) * pitch + (next() % 10) * 0.005;
    const double y = 0.5 * pitch + (i / columns) * pitch + (next() % 10) * 0.01;
    w.create_body(dynamic_box(x, y, half));
  }
}

// Boxes from 5 cm to 1.6 m: many sizes, many grid levels.
void mixed_pile(World& w) {
  pour(w, 11.0, 260, 0.025, 0.8, 777u);
}

// 2,600 boxes: more than a block of the threaded contact walk (kBlock), so the contacts of two
// threads are gathered in blocks and joined.
void big_pile(World& w) {
  pour(w, 29.0, 2600, 0.1, 0.4, 4242u);
}

std::vector<Case> cases() {
  // The pusher changes speed every 15 steps, so that the row is filed again as it goes.
  auto push_speeds = [](World& w, int k) {
    if (k % 15 == 0) w.set_velocity(BodyId{1}, {k % 30 == 0 ? 2.0 : 4.5, 0.0});
  };
  return {{"push_row", push_row, 180, push_speeds},
          {"rain", rain, 240},
          {"smash", smash, 200},
          {"bulldozer", bulldozer, 240},
          {"mixed_pile", mixed_pile, 300},
          {"big_pile", big_pile, 120}};
}

TEST(NearOrder, NoResultDependsOnWhenTheNearPairsWereScanned) {
  for (const Case& c : cases()) {
    for (const int threads : {1, 2}) {
      SCOPED_TRACE(c.name + ", threads " + std::to_string(threads));
      WorldDef def;
      def.threads = threads;
      // Which resting islands a step leaves out follows the near lists' history (islands.h; the
      // bits do not, island_test.cpp): here every body is solved, so the contacts compare.
      def.skip_rest = false;
      World as_it_comes(def), fresh(def);
      c.build(as_it_comes);
      c.build(fresh);
      detail::WorldAccess::impl(fresh).modern.rescan_every_step(true);
      const auto count = static_cast<std::uint32_t>(as_it_comes.body_count());
      std::uint64_t solved = 0;  // steps not skipped at rest (WorldDef::skip_rest)
      for (int k = 0; k < c.steps; ++k) {
        c.before_step(as_it_comes, k);
        c.before_step(fresh, k);
        as_it_comes.step(1.0 / 60.0);
        fresh.step(1.0 / 60.0);
        if (fresh.last_step_stats().skipped == 0) ++solved;
        ASSERT_EQ(bodies_apart(as_it_comes, fresh, count), 0u) << "after step " << k;
        // The last pass's contacts too, in the order found: those of bodies filed again since the
        // scan merged into the scan's by (later body, earlier body).
        const auto mine = detail::WorldAccess::impl(as_it_comes).modern.contacts();
        const auto theirs = detail::WorldAccess::impl(fresh).modern.contacts();
        ASSERT_TRUE(std::equal(
            mine.begin(), mine.end(), theirs.begin(), theirs.end(),
            [](const detail::Pair& p, const detail::Pair& q) { return p.a == q.a && p.b == q.b; }))
            << "contacts apart after step " << k;
      }
      const auto& reused = detail::WorldAccess::impl(as_it_comes).modern;
      const auto& scanned = detail::WorldAccess::impl(fresh).modern;
      // Not vacuous: the world as it comes took its near pairs from an earlier scan while bodies
      // had been filed again since, where its contacts and overlaps came through the merge.
      EXPECT_GT(reused.reuses_with_refiled(), 0u);
      EXPECT_LT(reused.scans(), solved);
      EXPECT_EQ(scanned.scans(), solved);
    }
  }
}

// The overlaps of a body as a chain gathers them (ChainState::gather_overlaps) are exactly the
// bodies a brute-force scan finds, in slot order, on each of its three paths: the near list alone
// (no body filed again came near), the near list with the overlay's stale bodies, and a stale
// body's own query of the grid. On the five size mixes, after 5% of the bodies were thrown far
// and the others moved within the refile distance.
TEST(NearOrder, AChainMeetsABodysOverlapsInSlotOrderOnEveryPath) {
  using namespace chain::detail;
  std::size_t by_path[3] = {0, 0, 0};  // near list alone, with the overlay, the grid: all mixes
  for (const Mix& m : kMixes) {
    SCOPED_TRACE(m.name);
    std::mt19937 rng(41);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    Bodies b = random_bodies(17, m.n, m.spread, m.min_half, m.max_half);
    Broadphase bp;
    bp.configure(b);
    bp.build(b);
    std::vector<Pair> near_pairs;
    bp.for_each_near_pair(b, [&](std::uint32_t i, std::uint32_t j) {
      near_pairs.push_back({i, j});
    });
    WorldDef def;
    StepStats stats;
    std::vector<CrushRecord> crushes;
    VelocityResponse response;
    Motion motion;
    WorkerPool pool;
    StageClock clock(false);
    StepProfile profile;
    StepContext ctx{b,      bp,    response, def,  stats, crushes, 1000,
                    motion, false, true,     pool, clock, profile, 1.0 / 60.0};
    ChainState state;
    state.begin_step(ctx);
    state.begin_pass(b, &near_pairs);
    for (std::uint32_t i = 0; i < b.dynamic_end; ++i) {
      const bool far = unit(rng) < 0.05;
      for (int k = 0; k < 2; ++k) {
        b.pos(k, i) +=
            far ? (unit(rng) - 0.5) * m.spread : (unit(rng) - 0.5) * bp.refile_distance();
      }
      bp.note_move(i, b.x(i), b.y(i));
    }
    const double tol = def.touch_tolerance;
    const std::vector<std::set<std::uint32_t>> overlaps = per_body(brute_force(b, tol), b.size());
    for (std::uint32_t i = 0; i < b.dynamic_end; ++i) {
      ++by_path[bp.stale(i) ? 2 : bp.near_stale(i) ? 1 : 0];
      std::vector<std::uint32_t> gathered;
      state.gather_overlaps(ctx, i, gathered);
      const std::vector<std::uint32_t> expected(overlaps[i].begin(), overlaps[i].end());
      EXPECT_EQ(gathered, expected) << "body " << i;
    }
  }
  for (const std::size_t count : by_path)
    EXPECT_GT(count, 0u);
}

}  // namespace
}  // namespace chain::testing
