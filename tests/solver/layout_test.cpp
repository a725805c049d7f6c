// After a step, the modern solver may store its bodies in the order that step reached them, so
// that the next steps walk memory front to back (solver/src/layout.h). A user must see nothing of
// it but the speed: ids, positions, velocities, touching flags and bits are the same as without.
#include "world_helpers.h"

#include <gtest/gtest.h>

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

TEST(Layout, Seed2014KeepsItsLayout) {
  World w(world_def(Variant::kSeed2014, VelocityRule::kZero));
  create_all(w, columns(0.0));
  for (int s = 0; s < 60; ++s) {
    w.step(kDt);
    EXPECT_EQ(w.last_step_stats().renumbered, 0u);
  }
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
