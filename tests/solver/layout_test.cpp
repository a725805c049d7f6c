// SPDX-License-Identifier: MIT
// After a step, the modern solver may store its bodies in the order that step reached them, so
// that the next steps walk memory front to back (solver/src/layout.h). A user must see nothing of
// it but the speed: every body keeps its id, its state and its flags, and results still depend on
// the bodies alone, not on the order they were created in.
#include "world_helpers.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <vector>

namespace chain::testing {
namespace {

constexpr double kDt = 1.0 / 60.0;

// 40 columns of 30 boxes each, of pseudo-random heights, standing on a floor: a pile whose layers
// (boxes the same number of contacts up) lie at different heights, so a Z-order of its centres is
// far from the order a step reaches them in. With gap > 0 the boxes start that far apart and the
// pile forms as they land.
std::vector<BodyDef> columns(double gap) {
  std::vector<BodyDef> defs{static_box(0.0, -1.0, 100.0, 1.0)};
  std::uint64_t state = 7;
  for (int c = 0; c < 40; ++c) {
    double y = gap;
    for (int k = 0; k < 30; ++k) {
      state = state * 6364136223846793005u + 1442695040888963407u;
      BodyDef d = dynamic_box(static_cast<double>(c) - 20.0, 0.0);
      d.half_extents.y = 0.3 + 0.4 * static_cast<double>(state >> 11) * 0x1.0p-53;
      d.center.y = y + d.half_extents.y;
      y += 2.0 * d.half_extents.y + gap;
      defs.push_back(d);
    }
  }
  return defs;
}

bool bits_equal(Vec2 a, Vec2 b) {
  return std::bit_cast<std::uint64_t>(a.x) == std::bit_cast<std::uint64_t>(b.x) &&
         std::bit_cast<std::uint64_t>(a.y) == std::bit_cast<std::uint64_t>(b.y);
}

std::vector<BodyId> create_all(World& w, const std::vector<BodyDef>& defs) {
  std::vector<BodyId> ids;
  for (const BodyDef& d : defs)
    ids.push_back(w.create_body(d));
  return ids;
}

TEST(Layout, RestingPileIsRenumberedOnceAndNothingMoves) {
  const std::vector<BodyDef> defs = columns(0.0);
  World w(world_def(Variant::kModern, VelocityRule::kInelastic));
  const std::vector<BodyId> ids = create_all(w, defs);
  w.step(kDt);
  ASSERT_EQ(w.last_step_stats().renumbered, 1u);  // the first step reaches a layer at a time
  for (std::size_t k = 1; k < defs.size(); ++k) {
    // The touching flags followed their bodies: each box lies on the one below (or the floor),
    // and every box but the top one of its column carries another.
    const bool top = (k - 1) % 30 == 29;
    EXPECT_TRUE(w.touching_flags(ids[k]) & touching::kBottom) << "box " << k;
    EXPECT_EQ((w.touching_flags(ids[k]) & touching::kTop) != 0, !top) << "box " << k;
  }
  int renumbered = 0;
  for (int s = 0; s < 300; ++s) {
    w.step(kDt);
    renumbered += static_cast<int>(w.last_step_stats().renumbered);
  }
  EXPECT_EQ(renumbered, 0);  // the pile rests: every later step reaches it in the same order
  for (std::size_t k = 1; k < defs.size(); ++k) {
    // Placed against its support every step, a resting box is rebuilt exactly where it stood.
    EXPECT_NEAR(w.position(ids[k]).x, defs[k].center.x, 1e-9) << "box " << k;
    EXPECT_NEAR(w.position(ids[k]).y, defs[k].center.y, 1e-9) << "box " << k;
    EXPECT_EQ(w.velocity(ids[k]).y, 0.0) << "box " << k;
  }
}

// A wall of equal columns: a Z-order of it lists the boxes of each layer in slot order, so a step
// that settles it a layer at a time never goes back in memory, but skips forward over the other
// layers at nearly every box (each layer a sweep over all of memory). That walk is renumbered
// too, once, and the wall stands exactly where it was built.
TEST(Layout, LayerWalkThatOnlySkipsForwardIsRenumbered) {
  std::vector<BodyDef> defs{static_box(0.0, -1.0, 100.0, 1.0)};
  for (int c = 0; c < 64; ++c) {
    for (int k = 0; k < 10; ++k)
      defs.push_back(dynamic_box(static_cast<double>(c) - 32.0, 0.5 + k));
  }
  World w(world_def(Variant::kModern, VelocityRule::kInelastic));
  const std::vector<BodyId> ids = create_all(w, defs);
  w.step(kDt);
  ASSERT_EQ(w.last_step_stats().renumbered, 1u);
  int renumbered = 0;
  for (int s = 0; s < 100; ++s) {
    w.step(kDt);
    renumbered += static_cast<int>(w.last_step_stats().renumbered);
  }
  EXPECT_EQ(renumbered, 0);  // walked front to back from then on
  for (std::size_t k = 1; k < defs.size(); ++k) {
    EXPECT_EQ(w.position(ids[k]).x, defs[k].center.x) << "box " << k;
    EXPECT_EQ(w.position(ids[k]).y, defs[k].center.y) << "box " << k;
  }
}

// Bodies no chain reaches move to the end of the order when the pile is renumbered, behind it:
// flying free they must keep their own velocity, drive, gravity scale and mass. Their paths are
// known exactly (semi-implicit Euler: v += g dt, then x += v dt), and two of them meet in the air
// after the renumbering and must conserve their momentum.
TEST(Layout, BodiesMovedByARenumberingKeepTheirState) {
  std::vector<BodyDef> defs = columns(0.0);
  const std::size_t first_free = defs.size();
  for (const double scale : {0.0, 0.5, 2.0}) {
    BodyDef d = dynamic_box(-60.0 + 10.0 * scale, 80.0, 0.25, 1.0 + scale);
    d.gravity_scale = scale;
    d.velocity = {0.5 - scale, 3.0 * scale};
    defs.push_back(d);
  }
  const std::size_t driven = defs.size();
  defs.push_back(dynamic_box(60.0, 90.0, 0.25));
  defs.back().gravity_scale = 0.0;
  // Floating, 3 m apart face to face, closing at 3 m/s: they meet after 1 s, at step 60.
  const std::size_t left = defs.size();
  for (const double x : {-2.0, 2.0}) {
    BodyDef d = dynamic_box(x, 120.0, 0.5, x < 0.0 ? 1.0 : 5.0);
    d.gravity_scale = 0.0;
    d.velocity = {x < 0.0 ? 2.0 : -1.0, 0.0};
    defs.push_back(d);
  }
  World w(world_def(Variant::kModern, VelocityRule::kInelastic));
  const std::vector<BodyId> ids = create_all(w, defs);
  w.set_drive(ids[driven], {-1.5, 0.25});
  w.step(kDt);
  ASSERT_EQ(w.last_step_stats().renumbered, 1u);
  constexpr int kSteps = 120;
  for (int s = 1; s < kSteps; ++s)
    w.step(kDt);

  const double t = kSteps * kDt;
  for (std::size_t k = first_free; k < driven; ++k) {
    const double g = -10.0 * defs[k].gravity_scale;
    const Vec2 v0 = defs[k].velocity, p0 = defs[k].center;
    EXPECT_NEAR(w.velocity(ids[k]).x, v0.x, 1e-12) << "body " << k;
    EXPECT_NEAR(w.velocity(ids[k]).y, v0.y + g * t, 1e-9) << "body " << k;
    EXPECT_NEAR(w.position(ids[k]).x, p0.x + v0.x * t, 1e-9) << "body " << k;
    EXPECT_NEAR(w.position(ids[k]).y, p0.y + v0.y * t + g * kDt * t * (kSteps + 1) / 2.0, 1e-9)
        << "body " << k;
  }
  EXPECT_NEAR(w.position(ids[driven]).x, 60.0 - 1.5 * t, 1e-9);
  EXPECT_NEAR(w.position(ids[driven]).y, 90.0 + 0.25 * t, 1e-9);
  // Momentum 1 * 2 + 5 * (-1) = -3 kg m/s before they met, shared after: -0.5 m/s each.
  EXPECT_NEAR(w.velocity(ids[left]).x, -0.5, 1e-12);
  EXPECT_NEAR(w.velocity(ids[left + 1]).x, -0.5, 1e-12);
}

// read_all walks the storage order a renumbering set: every body is listed once, with the state
// position() and velocity() give for its id; update_all keeps such a copy up to date.
TEST(Layout, ReadAllListsEveryBodyOnceWithItsState) {
  World w(world_def(Variant::kModern, VelocityRule::kInelastic));
  const std::vector<BodyId> ids = create_all(w, columns(0.05));
  for (int s = 0; s < 40; ++s)
    w.step(kDt);
  const std::size_t n = w.body_count();
  std::vector<BodyId> stored(n);
  std::vector<Vec2> p(n), v(n);
  w.read_all(stored, p, v);
  std::vector<int> seen(ids.size(), 0);
  bool reordered = false;
  for (std::size_t k = 0; k < n; ++k) {
    ASSERT_LT(stored[k].value, seen.size());
    ++seen[stored[k].value];
    reordered = reordered || stored[k] != ids[k];
    EXPECT_EQ(std::bit_cast<std::uint64_t>(p[k].x),
              std::bit_cast<std::uint64_t>(w.position(stored[k]).x));
    EXPECT_EQ(std::bit_cast<std::uint64_t>(p[k].y),
              std::bit_cast<std::uint64_t>(w.position(stored[k]).y));
    EXPECT_EQ(std::bit_cast<std::uint64_t>(v[k].x),
              std::bit_cast<std::uint64_t>(w.velocity(stored[k]).x));
    EXPECT_EQ(std::bit_cast<std::uint64_t>(v[k].y),
              std::bit_cast<std::uint64_t>(w.velocity(stored[k]).y));
  }
  EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), static_cast<std::ptrdiff_t>(n));
  EXPECT_TRUE(reordered) << "the pile was expected to be stored in an order of its own";
  // Outputs may be skipped; one shorter than the world is refused before anything is written.
  std::vector<Vec2> only(n);
  w.read_all({}, only, {});
  EXPECT_EQ(only[0].x, p[0].x);
  std::vector<Vec2> short_out(n - 1, Vec2{7.0, 7.0});
  EXPECT_THROW(w.read_all(stored, short_out, {}), std::invalid_argument);
  EXPECT_EQ(short_out[0].x, 7.0);

  // update_all brings the copy to what read_all reads now, and lists exactly the entries it
  // changed: while a box flies and lands, and once all rest (nothing).
  std::vector<std::uint32_t> changed;
  std::size_t changes = 0;
  w.set_velocity(ids.back(), {0.0, 3.0});  // a top box thrown up, to land again
  for (int s = 0; s < 200; ++s) {
    w.step(kDt);
    std::vector<BodyId> fresh_ids(n);
    std::vector<Vec2> fresh_p(n), fresh_v(n);
    w.read_all(fresh_ids, fresh_p, fresh_v);
    std::vector<std::uint32_t> want;
    for (std::uint32_t k = 0; k < n; ++k) {
      if (fresh_ids[k] != stored[k] || !bits_equal(fresh_p[k], p[k]) ||
          !bits_equal(fresh_v[k], v[k]))
        want.push_back(k);
    }
    w.update_all(stored, p, v, changed);
    ASSERT_EQ(changed, want) << "step " << s;
    for (std::uint32_t k = 0; k < n; ++k) {
      ASSERT_EQ(stored[k], fresh_ids[k]);
      ASSERT_TRUE(bits_equal(p[k], fresh_p[k]) && bits_equal(v[k], fresh_v[k]));
    }
    changes += changed.size();
  }
  EXPECT_GT(changes, 0u);
  EXPECT_TRUE(changed.empty()) << "the pile should rest again after 200 steps";
  EXPECT_THROW(w.update_all(stored, short_out, v, changed), std::invalid_argument);
}

// A game that adds a body every step makes the solver sort its bodies again every step; it is
// still renumbered at most once in Layout::kMinSteps (32) steps.
TEST(Layout, AWorldThatGainsABodyEveryStepIsRenumberedAtMostOnceIn32Steps) {
  World w(world_def(Variant::kModern, VelocityRule::kInelastic));
  create_all(w, columns(0.0));
  int renumberings = 0;
  for (int s = 0; s < 96; ++s) {
    w.create_body(dynamic_box(-80.0 + static_cast<double>(s), 200.0, 0.25));
    w.step(kDt);
    renumberings += static_cast<int>(w.last_step_stats().renumbered);
  }
  EXPECT_GE(renumberings, 1);
  EXPECT_LE(renumberings, 3);
}

// Three creation orders of a pile that forms while the test runs, so that it is renumbered in
// the middle of the run as well as after the first step: the same bits every time.
TEST(Layout, RenumberingGivesTheSameBitsForEveryCreationOrder) {
  const std::vector<BodyDef> defs = columns(0.3);
  const std::size_t n = defs.size();
  std::vector<std::vector<std::size_t>> orders(3);
  for (std::size_t k = 0; k < n; ++k) {
    orders[0].push_back(k);
    orders[1].push_back(n - 1 - k);
    orders[2].push_back((k * 7) % n);  // 7 and n = 1201 are coprime: a permutation
  }
  std::vector<std::vector<std::uint64_t>> bits;
  for (const std::vector<std::size_t>& order : orders) {
    World w(world_def(Variant::kModern, VelocityRule::kInelastic));
    std::vector<BodyId> id_of(n);
    for (const std::size_t k : order)
      id_of[k] = w.create_body(defs[k]);
    int late_renumberings = 0;
    for (int s = 0; s < 150; ++s) {
      w.step(kDt);
      if (s > 0) late_renumberings += static_cast<int>(w.last_step_stats().renumbered);
    }
    EXPECT_GT(late_renumberings, 0);
    std::vector<std::uint64_t>& out = bits.emplace_back();
    for (const BodyId id : id_of) {
      for (const Vec2 v : {w.position(id), w.velocity(id)}) {
        out.push_back(std::bit_cast<std::uint64_t>(v.x));
        out.push_back(std::bit_cast<std::uint64_t>(v.y));
      }
    }
  }
  EXPECT_EQ(bits[0], bits[1]);
  EXPECT_EQ(bits[0], bits[2]);
}

}  // namespace
}  // namespace chain::testing
