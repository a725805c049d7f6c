// SPDX-License-Identifier: MIT
// Bounded work: pyramids, long chains and dense piles finish every step within the budget, and
// a pyramid stands.
#include "world_helpers.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace chain::testing {
namespace {

constexpr double kDt = 1.0 / 60.0;

struct Scene {
  std::vector<BodyId> ids;
  std::vector<Vec2> half;
  std::vector<Vec2> start;
};

// The large-pyramid layout of engine benchmarks: rows of touching unit boxes on a static ground.
Scene build_pyramid(World& w, int base) {
  Scene s;
  s.ids.push_back(add_floor(w, 2.0 * static_cast<double>(base)));
  s.half.push_back({2.0 * static_cast<double>(base), 1.0});
  for (int row = 0; row < base; ++row) {
    for (int k = 0; k < base - row; ++k) {
      const double x = static_cast<double>(k) - 0.5 * static_cast<double>(base - row - 1);
      s.ids.push_back(w.create_body(dynamic_box(x, 0.5 + static_cast<double>(row))));
      s.half.push_back({0.5, 0.5});
    }
  }
  for (const BodyId id : s.ids)
    s.start.push_back(w.position(id));
  return s;
}

TEST(ChainWork, Base30PyramidStandsFor500Steps) {
  for (const VelocityRule rule : {VelocityRule::kZero, VelocityRule::kInelastic}) {
    World w(world_def(Variant::kModern, rule));
    const Scene s = build_pyramid(w, 30);
    for (int step = 0; step < 500; ++step) {
      w.step(kDt);
      ASSERT_EQ(w.last_step_stats().budget_hits, 0u);
    }
    double drift = 0.0;
    for (std::size_t i = 0; i < s.ids.size(); ++i) {
      const Vec2 p = w.position(s.ids[i]);
      drift = std::max(drift, std::hypot(p.x - s.start[i].x, p.y - s.start[i].y));
    }
    EXPECT_LT(drift, 0.01);
    EXPECT_LT(max_penetration(w, s.ids, s.half), 1e-3);
  }
}

// Each body joins a chain once: a pyramid costs work in proportion to its size. The 2014 chain
// has no visited set; it re-walks the pyramid from every supporting box and runs into its budget.
TEST(ChainWork, PyramidWorkIsLinearInModernAndExplodesInSeed2014) {
  auto calls = [](Variant v, int base) {
    World w(world_def(v, VelocityRule::kZero));
    build_pyramid(w, base);
    std::uint64_t total = 0;
    for (int step = 0; step < 10; ++step) {
      w.step(kDt);
      total += w.last_step_stats().resolve_calls;
    }
    return static_cast<double>(total) / 10.0;
  };
  const double modern10 = calls(Variant::kModern, 10), modern40 = calls(Variant::kModern, 40);
  const double boxes10 = 55.0, boxes40 = 820.0;
  EXPECT_LT(modern40 / boxes40, 2.0 * modern10 / boxes10);  // per-box work does not grow
  EXPECT_GT(calls(Variant::kSeed2014, 10), 4.0 * modern10);
}

// A heavy pusher hands almost all of its push down a 10,000-box row to the wall, so the chain
// really runs 10,000 deep (with a light pusher the overlap handed on shrinks as 1/k and falls
// below the touch tolerance long before the wall). 10 cm boxes keep double spacing fine.
TEST(ChainWork, TenThousandBoxRowIntoAWallChainsFullyAndNothingMoves) {
  for (const Variant v : {Variant::kModern, Variant::kSeed2014}) {
    World w(world_def(v, VelocityRule::kInelastic, {0.0, 0.0}));
    const int n = 10000;
    const BodyId pusher = w.create_body(dynamic_box(0.0, 0.0, 0.05, 1.0e6));
    std::vector<BodyId> row;
    for (int i = 1; i <= n; ++i) {
      row.push_back(w.create_body(dynamic_box(0.1 * static_cast<double>(i), 0.0, 0.05)));
    }
    w.create_body(static_box(0.1 * static_cast<double>(n + 1), 0.0, 0.05, 1.0));
    w.set_drive(pusher, {1.0, 0.0});
    for (int step = 0; step < 3; ++step)
      w.step(kDt);
    if (v == Variant::kModern) {
      EXPECT_EQ(w.last_step_stats().budget_hits, 0u);
      EXPECT_GE(w.last_step_stats().max_depth, static_cast<std::uint32_t>(n));
      EXPECT_NEAR(w.position(pusher).x, 0.0, 1e-3);
      EXPECT_NEAR(w.position(row[n / 2]).x, 0.1 * static_cast<double>(n / 2 + 1), 1e-3);
    } else {
      // Recursion is capped at seed_max_depth: the cut is counted, never a crash.
      EXPECT_GT(w.last_step_stats().budget_hits, 0u);
      EXPECT_LE(w.last_step_stats().max_depth, static_cast<std::uint32_t>(w.def().seed_max_depth));
    }
  }
}

// 400 boxes created deep inside each other, in 15 columns, each column's boxes as wide as each
// other and no taller than wide: every pair overlaps more across than up, so push-out separates
// them vertically. (Boxes whose centres nearly coincide across their widths get a sideways push
// instead, and can jam a row wider than its room: RowWiderThanItsGapIsCrushedNotLooped.) They
// settle within the budget to under 1 mm of overlap.
TEST(ChainWork, DenseOverlappingPileStaysWithinBudgetAndSeparates) {
  World w(world_def(Variant::kModern, VelocityRule::kInelastic));
  std::vector<BodyId> ids = {w.create_body(static_box(0.0, -1.0, 30.0, 1.0)),
                             w.create_body(static_box(-11.0, 16.0, 1.0, 16.0)),
                             w.create_body(static_box(11.0, 16.0, 1.0, 16.0))};
  std::vector<Vec2> half = {{30.0, 1.0}, {1.0, 16.0}, {1.0, 16.0}};
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> y(0.5, 8.0), unit(0.0, 1.0);
  double column_half[15];
  for (double& h : column_half)
    h = 0.2 + 0.4 * unit(rng);
  for (int i = 0; i < 400; ++i) {
    const int c = i % 15;
    const double hx = column_half[c], hy = 0.2 + (hx - 0.2) * unit(rng);
    BodyDef d = dynamic_box(1.3 * (c - 7), y(rng), hx, 4.0 * hx * hy);
    d.half_extents = {hx, hy};
    ids.push_back(w.create_body(d));
    half.push_back({hx, hy});
  }
  const std::uint64_t budget =
      static_cast<std::uint64_t>(w.def().budget_per_body) * ids.size() + 1024;
  double first = 0.0;
  for (int step = 0; step < 300; ++step) {
    w.step(kDt);
    ASSERT_LE(w.last_step_stats().resolve_calls, budget);
    if (step == 0) first = max_penetration(w, ids, half);
  }
  EXPECT_GT(first, 0.0);
  EXPECT_LT(max_penetration(w, ids, half), 1e-3);
  EXPECT_EQ(w.last_step_stats().crush_events, 0u);
}

// The layout of the harness's overlapping_pile stress case: n boxes of half extent 0.3 to 0.5 m
// dropped at random into a container half as tall as they need, on a floor between two walls.
std::vector<BodyId> overlapping_pile(World& w, int n, std::uint32_t seed) {
  std::mt19937 rng(seed);
  const double width = std::max(6.0, std::sqrt(static_cast<double>(n)));
  const double height = 0.5 * static_cast<double>(n) / width;
  std::vector<BodyId> ids = {add_floor(w, 0.5 * width + 2.0)};
  const double wall = 4.0 * height + 10.0;
  ids.push_back(w.create_body(static_box(-0.5 * width - 0.5, 0.5 * wall, 0.5, 0.5 * wall)));
  ids.push_back(w.create_body(static_box(0.5 * width + 0.5, 0.5 * wall, 0.5, 0.5 * wall)));
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int i = 0; i < n; ++i) {
    const double h = 0.3 + 0.2 * unit(rng);
    const double x = -0.5 * width + h + (width - 2.0 * h) * unit(rng);
    ids.push_back(w.create_body(dynamic_box(x, h + height * unit(rng), h, 4.0 * h * h)));
  }
  return ids;
}

// Issue 2: one step of a 100,000-box overlapping pile did not end in 600 s. Pushes sent bodies
// far, the broadphase widened every later query by the largest push of the step, and the queries
// scanned most of the pile: work per body grew with the pile, quadratic in all. Bodies that move
// far are now filed again where they are. The search work per body (candidates the broadphase
// examined) is then much the same in a pile ten times larger, a few hundred times the step's
// other work (pair resolutions, bounded by the budget, contacts and bodies), where widened queries
// would scan thousands of bodies each.
TEST(ChainWork, OverlappingPileStepSearchWorkPerBodyIsBounded) {
  double per_body[2] = {0.0, 0.0};
  const int sizes[2] = {2000, 20000};
  for (int k = 0; k < 2; ++k) {
    const int n = sizes[k];
    World w(world_def(Variant::kModern, VelocityRule::kInelastic));
    overlapping_pile(w, n, 5);
    for (int step = 0; step < 2; ++step) {
      w.step(kDt);
      const StepStats& st = w.last_step_stats();
      const double work = static_cast<double>(st.resolve_calls) + st.contacts + n;
      EXPECT_LT(st.candidates, 500.0 * work) << "n " << n << " step " << step;
      per_body[k] = std::max(per_body[k], st.candidates / static_cast<double>(n));
    }
  }
  EXPECT_LT(per_body[1], 2.0 * per_body[0]) << "per body at 2,000: " << per_body[0];
}

// Boxes created all in one place: every query a resolution makes meets every box of the pile, so
// a budget on resolutions alone let one step of 3,000 such boxes take 41 s (each of its 193,000
// resolutions examined and sorted 3,000 bodies). A gathering that meets many bodies now costs
// the budget in proportion (StepContext::charge_met): the step's search work is then a small
// multiple of the pairs the pile holds, its contacts (4-42 times at 200 and 800 boxes), where it
// was 600-870 times them; the bound, 100, lies between.
TEST(ChainWork, APileInOnePlaceSearchesInProportionToItsPairs) {
  for (const int n : {200, 800}) {
    World w(world_def(Variant::kModern, VelocityRule::kInelastic));
    add_floor(w, 20.0);
    for (int i = 0; i < n; ++i)
      w.create_body(dynamic_box(0.0, 0.5));
    for (int step = 0; step < 3; ++step) {
      w.step(kDt);
      const StepStats& st = w.last_step_stats();
      const double pairs = static_cast<double>(st.contacts) + n;
      EXPECT_LT(st.candidates, 100.0 * pairs) << "n " << n << " step " << step;
    }
    if (n > 200) continue;
    // Fewer resolutions a step, but the pile still comes apart, over more steps: 200 boxes
    // within two seconds (27 steps; 800 take 454), no step then cut, each box touching a few
    // others.
    for (int step = 3; step < 120; ++step)
      w.step(kDt);
    EXPECT_EQ(w.last_step_stats().budget_hits, 0u) << "n " << n;
    EXPECT_LT(w.last_step_stats().contacts, 3u * static_cast<unsigned>(n)) << "n " << n;
  }
}

// A fast body used to widen the broadphase's one global displacement margin: the step after the
// sweep rebuilt the grid and rescanned the near pairs, which roughly doubled a step of a resting
// pyramid with one fast box flying past. The box is now filed again where continuous collision left
// it, and its build serves the whole step.
TEST(ChainWork, OneFastBodyDoesNotDoubleAStepsSearchWork) {
  constexpr int kSteps = 30;
  // Candidates examined by the first step (which builds the grid and scans the near pairs) and by
  // all kSteps steps.
  auto candidates = [](bool with_fast, double& first) {
    World w(world_def(Variant::kModern, VelocityRule::kInelastic));
    build_pyramid(w, 40);
    if (with_fast) {
      BodyDef shot = dynamic_box(-200.0, 60.0, 0.1);
      shot.gravity_scale = 0.0;
      shot.velocity = {600.0, 0.0};
      w.create_body(shot);
    }
    double total = 0.0;
    for (int step = 0; step < kSteps; ++step) {
      w.step(kDt);
      if (with_fast) {
        EXPECT_EQ(w.last_step_stats().fast_bodies, 1u);
      }
      if (step == 0) first = w.last_step_stats().candidates;
      total += w.last_step_stats().candidates;
    }
    return total;
  };
  double scan = 0.0, unused = 0.0;
  const double resting = candidates(false, scan), with_fast = candidates(true, unused);
  // The fast box's own query along its path is all it adds: far less than a grid scan a step.
  EXPECT_LT((with_fast - resting) / kSteps, 0.25 * scan) << "resting " << resting;
}

// A flock going steadily (a train, a pushed row, a blade's crates) moved every body further than
// the broadphase's refile distance every step, so every step filed them all again and scanned
// every near pair anew. Filed at their boxes stretched along their way (Broadphase::build), they
// stay where they are filed for Broadphase::kAheadSteps steps: a step that scans the near pairs
// (and so examines at least one candidate per body) comes once in that many, not every step.
TEST(ChainWork, AFlockGoingSteadilyIsNotScannedAgainEveryStep) {
  constexpr int kSteps = 64, kSide = 20;
  WorldDef def = world_def(Variant::kModern, VelocityRule::kInelastic, {0.0, 0.0});
  World w(def);
  for (int i = 0; i < kSide; ++i) {
    for (int j = 0; j < kSide; ++j) {
      BodyDef d = dynamic_box(2.0 * i, 2.0 * j);
      d.velocity = {4.0, -1.0};  // 67 mm a step: twice the 31 mm refile distance of 1 m boxes
      w.create_body(d);
    }
  }
  int scans = 0;
  for (int step = 0; step < kSteps; ++step) {
    w.step(kDt);
    ASSERT_EQ(w.last_step_stats().fast_bodies, 0u);  // no sweep: its queries would count too
    scans += w.last_step_stats().candidates >= kSide * kSide;
  }
  EXPECT_GE(scans, 1);
  EXPECT_LE(scans, kSteps / 4);
}

// Five 1 m boxes between walls 4 m apart cannot all fit: every step ends, reports the squeeze,
// and keeps every box between the walls.
TEST(ChainWork, RowWiderThanItsGapIsCrushedNotLooped) {
  World w(world_def(Variant::kModern, VelocityRule::kInelastic, {0.0, 0.0}));
  w.create_body(static_box(-2.5, 0.0, 0.5, 2.0));
  w.create_body(static_box(2.5, 0.0, 0.5, 2.0));
  std::vector<BodyId> row;
  for (int i = 0; i < 5; ++i)
    row.push_back(w.create_body(dynamic_box(-1.6 + 0.8 * i, 0.0)));
  for (int step = 0; step < 60; ++step) {
    w.step(kDt);
    ASSERT_GE(w.last_step_stats().crush_events, 1u);
    ASSERT_EQ(w.last_step_stats().budget_hits, 0u);
  }
  for (const BodyId id : row) {
    EXPECT_GE(w.position(id).x, -2.0);
    EXPECT_LE(w.position(id).x, 2.0);
  }
}

// Issue 4: two kinematic walls closing in on a row of touching boxes (top-down, no gravity). The
// row used to take the whole squeeze at one contact, which grew every step until the boxes there
// passed each other and flew (4.5 m/s with walls at 0.5 m/s). The squeeze is spread over the row:
// after time t the walls have closed 2 v t, every one of the n + 1 contacts overlaps by
// e = 2 v t / (n + 1), and box i is centred at the left face + (2i + 1) h - (i + 1) e, where the
// left face is at -n h + v t. No box moves faster than the walls, and every box is reported
// crushed between them, every step.
TEST(ChainWork, ConvergingWallsSpreadTheSqueezeEvenlyOverTheRow) {
  for (const VelocityRule rule : {VelocityRule::kZero, VelocityRule::kInelastic}) {
    for (const int n : {1, 2, 3, 5, 10, 50, 300}) {
      for (const double v : {0.2, 0.5, 2.0}) {
        World w(world_def(Variant::kModern, rule, {0.0, 0.0}));
        const double h = 0.5, half_row = n * h;
        w.create_body(kinematic_box(-half_row - 0.5, 0.0, 0.5, 2.0, {v, 0.0}));
        w.create_body(kinematic_box(half_row + 0.5, 0.0, 0.5, 2.0, {-v, 0.0}));
        std::vector<BodyId> row;
        for (int i = 0; i < n; ++i)
          row.push_back(w.create_body(dynamic_box(-half_row + h + 2.0 * h * i, 0.0)));
        std::vector<double> before(static_cast<std::size_t>(n));
        // Until the walls have closed a quarter of a box per contact.
        const int steps = std::min(240, static_cast<int>(0.25 * (n + 1) / (2.0 * v * kDt)));
        for (int s = 1; s <= steps; ++s) {
          for (int i = 0; i < n; ++i)
            before[static_cast<std::size_t>(i)] = w.position(row[static_cast<std::size_t>(i)]).x;
          w.step(kDt);
          const double t = s * kDt, e = 2.0 * v * t / (n + 1), left = -half_row + v * t;
          ASSERT_EQ(w.crush_events().size(), static_cast<std::size_t>(n))
              << "n " << n << " v " << v << " step " << s;
          for (int i = 0; i < n; ++i) {
            const double x = w.position(row[static_cast<std::size_t>(i)]).x;
            ASSERT_NEAR(x, left - (i + 1) * e + (2 * i + 1) * h, 1e-9 * (1.0 + half_row))
                << "n " << n << " v " << v << " step " << s << " box " << i;
            ASSERT_LE(std::abs(x - before[static_cast<std::size_t>(i)]) / kDt, v + 1e-6)
                << "n " << n << " v " << v << " step " << s << " box " << i;
          }
        }
        EXPECT_EQ(w.last_step_stats().budget_hits, 0u);
      }
    }
  }
}

TEST(ChainWork, ExhaustedBudgetIsCountedAndTheStepStillEnds) {
  WorldDef d = world_def(Variant::kModern, VelocityRule::kZero);
  d.budget_per_body = 1;
  World w(d);
  std::vector<BodyId> ids = {add_floor(w)};
  for (int i = 0; i < 200; ++i) {  // 200 boxes created inside each other
    ids.push_back(w.create_body(dynamic_box(0.01 * static_cast<double>(i), 0.5)));
  }
  w.step(kDt);
  EXPECT_GT(w.last_step_stats().budget_hits, 0u);
  EXPECT_LE(w.last_step_stats().resolve_calls, 201u + 1024u);
}

}  // namespace
}  // namespace chain::testing
