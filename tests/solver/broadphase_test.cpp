// The broadphase finds exactly the overlapping pairs a brute-force scan finds, whatever the
// mix of sizes, and still finds a pair after a push moved a body out of its cell.
#include "broadphase.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>
#include <utility>

namespace chain::detail {
namespace {

using Pairs = std::set<std::pair<std::uint32_t, std::uint32_t>>;

Bodies random_bodies(std::uint32_t seed, int n, double spread, double min_half, double max_half) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> pos(-spread, spread), half(min_half, max_half), kind(0, 1);
  Bodies b;
  for (int i = 0; i < n; ++i) {
    BodyDef d;
    const double k = kind(rng);
    d.type = k < 0.8 ? BodyType::kDynamic : (k < 0.9 ? BodyType::kKinematic : BodyType::kStatic);
    d.center = {pos(rng), pos(rng)};
    d.half_extents = {half(rng), half(rng)};
    b.append(d, static_cast<std::uint32_t>(i));
  }
  BodyDef ground;
  ground.type = BodyType::kStatic;
  ground.center = {0.0, -spread};
  ground.half_extents = {spread * 2.0, 1.0};
  b.append(ground, static_cast<std::uint32_t>(n));
  std::vector<std::uint32_t> slot_of_id(b.size());
  b.canonicalize(slot_of_id);
  return b;
}

Pairs brute_force(const Bodies& b, double tol) {
  Pairs out;
  for (std::uint32_t i = 0; i < b.size(); ++i) {
    for (std::uint32_t j = i + 1; j < b.size(); ++j) {
      if (b.immovable(i) && b.immovable(j)) continue;
      const double ox = std::min(b.x(i) + b.hx(i), b.x(j) + b.hx(j)) -
                        std::max(b.x(i) - b.hx(i), b.x(j) - b.hx(j));
      const double oy = std::min(b.y(i) + b.hy(i), b.y(j) + b.hy(j)) -
                        std::max(b.y(i) - b.hy(i), b.y(j) - b.hy(j));
      if (ox > tol && oy > tol) out.insert({i, j});
    }
  }
  return out;
}

struct Mix {
  const char* name;
  int n;
  double spread, min_half, max_half;
};
void PrintTo(const Mix& c, std::ostream* os) {
  *os << c.name;
}

class BroadphasePairs : public ::testing::TestWithParam<Mix> {};

INSTANTIATE_TEST_SUITE_P(Solver, BroadphasePairs,
                         ::testing::Values(Mix{"UniformDense", 600, 10.0, 0.4, 0.6},
                                           Mix{"MixedSizes", 500, 20.0, 0.05, 3.0},
                                           Mix{"TinyAndHuge", 300, 50.0, 0.001, 40.0},
                                           Mix{"SparseFarApart", 200, 1.0e5, 0.5, 1.0},
                                           Mix{"FarFromOrigin", 300, 1.0e6, 0.5, 2000.0}),
                         [](const auto& info) { return std::string(info.param.name); });

TEST_P(BroadphasePairs, MatchBruteForce) {
  const Mix m = GetParam();
  for (std::uint32_t seed = 1; seed <= 3; ++seed) {
    const Bodies b = random_bodies(seed, m.n, m.spread, m.min_half, m.max_half);
    Broadphase bp;
    bp.configure(b);
    bp.build(b);
    Pairs near;
    bp.for_each_near_pair([&](std::uint32_t i, std::uint32_t j) {
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
  b.canonicalize(slot_of_id);
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

}  // namespace
}  // namespace chain::detail
