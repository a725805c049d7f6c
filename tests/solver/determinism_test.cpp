// SPDX-License-Identifier: MIT
// Modern results depend on the bodies, never on the order they were created in, and repeat to
// the bit. The 2014 variant is order-dependent by design; one test pins that down.
#include "world_helpers.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <numeric>
#include <random>
#include <vector>

namespace chain::testing {
namespace {

constexpr double kDt = 1.0 / 60.0;

// Stacks, a driven pusher against a row, a falling heavy box, a rising lift, a wall and a
// squeeze under a ceiling: every kind of contact the solver knows.
std::vector<BodyDef> mixed_scene() {
  std::vector<BodyDef> defs;
  defs.push_back(static_box(0.0, -1.0, 40.0, 1.0));  // floor
  defs.push_back(static_box(12.0, 3.0, 0.5, 3.0));   // wall
  defs.push_back(static_box(-10.0, 3.1, 2.0, 0.5));  // ceiling over the lift
  for (int i = 0; i < 5; ++i) {
    defs.push_back(
        dynamic_box(-4.0, 0.5 + static_cast<double>(i), 0.5, 1.0 + static_cast<double>(i)));
  }
  for (int i = 0; i < 6; ++i)
    defs.push_back(dynamic_box(2.0 + static_cast<double>(i), 0.5));
  defs.push_back(dynamic_box(1.0, 0.5, 0.5, 3.0));   // the pusher (driven below)
  defs.push_back(dynamic_box(4.3, 4.0, 1.0, 20.0));  // heavy box falling onto the row
  defs.push_back(kinematic_box(-10.0, 0.25, 1.5, 0.25, {0.0, 0.5}));  // rising lift
  defs.push_back(dynamic_box(-10.0, 1.0, 0.5, 2.0));                  // rider, to be squeezed
  BodyDef bouncy = dynamic_box(-6.0, 3.0, 0.3, 0.5);
  bouncy.restitution = 0.6;
  bouncy.velocity = {1.5, -2.0};
  defs.push_back(bouncy);
  return defs;
}

constexpr std::size_t kPusher = 14;

struct Drive {
  std::size_t body;
  Vec2 velocity;
  DriveAxes axes;
};

// A level: a floor of flush tiles of uneven widths with boxes sliding and landing across the
// joins, a wall of stacked tiles with a box driven into it, rough crates on a moving platform and
// on the floor, a character walking (x held) off a ledge, a projectile fired into a stack and a
// crate falling fast onto a thin slab.
std::vector<BodyDef> level_scene(std::vector<Drive>& drives) {
  std::vector<BodyDef> defs;
  double x = -20.0;
  for (int i = 0; i < 14; ++i) {  // floor tiles, top at y = 0
    const double width = 0.4 + 0.37 * static_cast<double>((i * 7) % 5);
    BodyDef tile = static_box(x + 0.5 * width, -0.5, 0.5 * width, 0.5);
    tile.friction = i % 2 == 0 ? 0.0 : 0.6;
    defs.push_back(tile);
    x += width;
  }
  for (int i = 0; i < 6; ++i)  // a wall of stacked tiles, its face at x = -20
    defs.push_back(static_box(-20.5, 0.7 * i + 0.35, 0.5, 0.35));
  BodyDef slider = dynamic_box(-15.0, 0.25, 0.25, 2.0);
  slider.velocity = {4.0, 0.0};
  defs.push_back(slider);
  BodyDef fast_slider = dynamic_box(-10.0, 0.2, 0.2);
  fast_slider.velocity = {-35.0, 0.0};
  defs.push_back(fast_slider);
  defs.push_back(dynamic_box(-13.37, 3.0, 0.3));   // lands across a join
  BodyDef climber = dynamic_box(-19.7, 5.0, 0.3);  // driven into the wall, slides down it
  defs.push_back(climber);
  drives.push_back({defs.size() - 1, {-1.0, 0.0}, DriveAxes::kX});
  BodyDef platform = kinematic_box(5.0, -0.5, 3.0, 0.5, {1.5, 0.0});
  platform.friction = 1.0;
  defs.push_back(platform);
  for (int i = 0; i < 3; ++i) {
    BodyDef crate = dynamic_box(5.0, 0.25 + 0.5 * i, 0.25, 1.0 + i);
    crate.friction = 0.8;
    defs.push_back(crate);
  }
  defs.push_back(static_box(20.0, 1.0, 3.0, 0.5));  // a ledge, top at 1.5
  defs.push_back(dynamic_box(19.0, 1.75, 0.25));
  drives.push_back({defs.size() - 1, {3.0, 0.0}, DriveAxes::kX});
  for (int i = 0; i < 4; ++i)
    defs.push_back(dynamic_box(30.0, 0.5 + i));
  defs.push_back(static_box(31.0, 2.0, 0.5, 2.0));  // backstop
  BodyDef shot = dynamic_box(26.5, 1.5, 0.1);
  shot.gravity_scale = 0.0;
  shot.velocity = {400.0, 0.0};
  defs.push_back(shot);
  defs.push_back(static_box(40.0, 0.0, 1.0, 0.05));  // thin slab
  BodyDef faller = dynamic_box(40.0, 3.0, 0.25);
  faller.velocity = {0.5, -30.0};
  defs.push_back(faller);
  return defs;
}

std::vector<Vec2> run_in_order(const std::vector<BodyDef>& defs,
                               const std::vector<std::size_t>& order, WorldDef def, int steps,
                               const std::vector<Drive>& drives = {
                                   {kPusher, {1.5, 0.0}, DriveAxes::kBoth}}) {
  World w(def);
  std::vector<BodyId> id_of(defs.size());
  for (const std::size_t k : order)
    id_of[k] = w.create_body(defs[k]);
  for (const Drive& d : drives)
    w.set_drive(id_of[d.body], d.velocity, d.axes);
  for (int s = 0; s < steps; ++s)
    w.step(kDt);
  std::vector<Vec2> out;
  for (const BodyId id : id_of) {
    out.push_back(w.position(id));
    out.push_back(w.velocity(id));
  }
  return out;
}

bool same_bits(const std::vector<Vec2>& a, const std::vector<Vec2>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (std::bit_cast<std::uint64_t>(a[i].x) != std::bit_cast<std::uint64_t>(b[i].x) ||
        std::bit_cast<std::uint64_t>(a[i].y) != std::bit_cast<std::uint64_t>(b[i].y)) {
      return false;
    }
  }
  return true;
}

std::vector<std::vector<std::size_t>> permutations(std::size_t n) {
  std::vector<std::size_t> identity(n);
  std::iota(identity.begin(), identity.end(), std::size_t{0});
  std::vector<std::vector<std::size_t>> out = {identity, {identity.rbegin(), identity.rend()}};
  std::mt19937 rng(2014);
  for (int k = 0; k < 5; ++k) {
    std::vector<std::size_t> p = identity;
    std::shuffle(p.begin(), p.end(), rng);
    out.push_back(p);
  }
  return out;
}

class OrderIndependence : public ::testing::TestWithParam<VelocityRule> {};

INSTANTIATE_TEST_SUITE_P(Modern, OrderIndependence,
                         ::testing::Values(VelocityRule::kZero, VelocityRule::kInelastic),
                         [](const auto& info) {
                           return info.param == VelocityRule::kZero ? "zero" : "inelastic";
                         });

TEST_P(OrderIndependence, EveryCreationOrderGivesTheSameBits) {
  const std::vector<BodyDef> defs = mixed_scene();
  const WorldDef def = world_def(Variant::kModern, GetParam());
  const auto orders = permutations(defs.size());
  const std::vector<Vec2> reference = run_in_order(defs, orders[0], def, 240);
  for (std::size_t k = 1; k < orders.size(); ++k) {
    EXPECT_TRUE(same_bits(reference, run_in_order(defs, orders[k], def, 240)))
        << "permutation " << k;
  }
}

TEST_P(OrderIndependence, LevelWithSeamsFastBodiesFrictionAndDrivesGivesTheSameBits) {
  std::vector<Drive> drives;
  const std::vector<BodyDef> defs = level_scene(drives);
  const WorldDef def = world_def(Variant::kModern, GetParam());
  const auto orders = permutations(defs.size());
  const std::vector<Vec2> reference = run_in_order(defs, orders[0], def, 180, drives);
  for (std::size_t k = 1; k < orders.size(); ++k) {
    EXPECT_TRUE(same_bits(reference, run_in_order(defs, orders[k], def, 180, drives)))
        << "permutation " << k;
  }
}

TEST(Determinism, RepeatedRunsGiveTheSameBits) {
  const std::vector<BodyDef> defs = mixed_scene();
  const auto order = permutations(defs.size())[3];
  for (const Variant v : {Variant::kModern, Variant::kSeed2014}) {
    const WorldDef def = world_def(v, VelocityRule::kInelastic);
    EXPECT_TRUE(same_bits(run_in_order(defs, order, def, 200), run_in_order(defs, order, def, 200)))
        << variant_name(v);
  }
}

TEST(Determinism, CopiedWorldContinuesIdentically) {
  World w(world_def(Variant::kModern, VelocityRule::kInelastic));
  std::vector<BodyId> ids;
  for (const BodyDef& d : mixed_scene())
    ids.push_back(w.create_body(d));
  for (int s = 0; s < 50; ++s)
    w.step(kDt);
  World copy = w;
  for (int s = 0; s < 50; ++s) {
    w.step(kDt);
    copy.step(kDt);
  }
  for (const BodyId id : ids) {
    EXPECT_EQ(std::bit_cast<std::uint64_t>(w.position(id).x),
              std::bit_cast<std::uint64_t>(copy.position(id).x));
    EXPECT_EQ(std::bit_cast<std::uint64_t>(w.position(id).y),
              std::bit_cast<std::uint64_t>(copy.position(id).y));
  }
}

// docs/algorithm-2014.md Quirk 2 (§3.5): a body squeezed between two statics ends inside one of
// them, and which one depends on the order the pairs are met. Modern centres it, whatever the
// order.
TEST(Determinism, SqueezeOutcomeDependsOnCreationOrderOnlyInSeed2014) {
  const std::vector<BodyDef> defs = {static_box(0.0, -1.0, 5.0, 1.0),  // floor, top at 0
                                     static_box(0.0, 1.8, 5.0, 1.0),   // ceiling, bottom at 0.8
                                     dynamic_box(0.0, 0.45)};          // 1 m box in 0.8 m
  auto final_y = [&](Variant v, bool floor_first) {
    World w(world_def(v, VelocityRule::kZero, {0.0, 0.0}));
    BodyId box;
    if (floor_first) {
      w.create_body(defs[0]), w.create_body(defs[1]), box = w.create_body(defs[2]);
    } else {
      w.create_body(defs[1]), w.create_body(defs[0]), box = w.create_body(defs[2]);
    }
    w.step(kDt);
    return w.position(box).y;
  };
  EXPECT_NE(final_y(Variant::kSeed2014, true), final_y(Variant::kSeed2014, false));
  EXPECT_EQ(final_y(Variant::kModern, true), final_y(Variant::kModern, false));
  EXPECT_NEAR(final_y(Variant::kModern, true), 0.4, 1e-12);  // midway between 0 and 0.8
}

// Two bodies created apart (bodies 0 and 3 below: same size and mass, different centres and
// velocities) are pushed into one state, bit for bit; destroying a third body re-sorts the world.
// The tie is broken by what each was created as, never by creation order, so each body keeps its
// own path whichever order the world was built in. (The fuzzer's reproducer,
// tests/fuzz/corpus/world/creation_order_tie_*.bin, decoded.)
TEST(Determinism, BodiesCreatedApartInOneStateKeepTheirPathsAcrossADestroy) {
  struct Row {
    BodyType type;
    double x, y, hx, hy, vx, vy, mass, gravity_scale, restitution;
  };
  constexpr BodyType D = BodyType::kDynamic, S = BodyType::kStatic;
  const std::vector<Row> rows = {
      {D, -6.875, -2.375, 1.6875, 1.6875, -0.75, -4.75, 0.001, 0.0, 0.0},
      {D, -2.375, -2.375, 1.6875, 1.6875, -4.75, -4.75, 0.001, 0.0, 1.0},
      {S, -2.375, -2.375, 1.6875, 1.6875, 0, 0, 1, 1, 0},
      {D, -2.375, -2.375, 1.6875, 1.6875, -4.75, -4.75, 0.001, 0.0, 0.0},
      {D, -2.375, -2.375, 1.6875, 2.0, 15.875, 15.875, 100.0, 1.0, 0.5},  // driven to (-8, -8)
      {S, 7.9375, 0.3125, 0.125, 0.0625, 0, 0, 1, 1, 0},
      {S, -6.4375, -8.0, 0.0625, 0.0625, 0, 0, 1, 1, 0},
      {S, -8.0, -8.0, 0.0625, 0.625, 0, 0, 1, 1, 0},
      {S, 5.0, -2.4375, 1.3125, 0.0625, 0, 0, 1, 1, 0},
      {S, -2.0, -8.0, 0.0625, 1.8125, 0, 0, 1, 1, 0},
      {S, -8.0, -2.0, 0.0625, 0.0625, 0, 0, 1, 1, 0},
      {S, -7.25, 3.5, 0.5, 0.8125, 0, 0, 1, 1, 0},
      {D, -6.375, 5.25, 1.875, 0.625, -8.875, 9.25, 1.0, 1.0, 1.0},
      {S, 0.6875, 2.125, 0.0625, 0.0625, 0, 0, 1, 1, 0},
      {S, -8.0, -8.0, 0.0625, 0.875, 0, 0, 1, 1, 0},
      {S, -8.0, -7.6875, 1.5625, 0.625, 0, 0, 1, 1, 0},
      {S, 0.1875, 5.25, 0.5625, 0.1875, 0, 0, 1, 1, 0},
      {S, -8.0, -8.0, 0.0625, 0.0625, 0, 0, 1, 1, 0},
      {S, -8.0, -8.0, 0.875, 1.5625, 0, 0, 1, 1, 0},
  };
  WorldDef def = world_def(Variant::kModern, VelocityRule::kZero, {-8.90625, 10.9375});
  def.max_passes = 2;
  def.budget_per_body = 111;
  auto final_positions = [&](bool reversed) {
    World w(def);
    std::vector<BodyId> ids(rows.size());
    for (std::size_t k = 0; k < rows.size(); ++k) {
      const std::size_t i = reversed ? rows.size() - 1 - k : k;
      const Row& r = rows[i];
      BodyDef b;
      b.type = r.type;
      b.center = {r.x, r.y};
      b.half_extents = {r.hx, r.hy};
      if (r.type != S) b.velocity = {r.vx, r.vy};
      b.mass = r.mass;
      b.gravity_scale = r.gravity_scale;
      b.restitution = r.restitution;
      ids[i] = w.create_body(b);
      if (i == 4) w.set_drive(ids[i], {-8.0, -8.0});
    }
    for (int step = 0; step < 26; ++step) {
      if (step == 18) w.destroy_body(ids[2]);
      w.step(1.0 / 240.0);
    }
    std::vector<Vec2> out;
    for (std::size_t i = 0; i < rows.size(); ++i) {
      if (i != 2) out.push_back(w.position(ids[i]));
    }
    return out;
  };
  EXPECT_TRUE(same_bits(final_positions(false), final_positions(true)));
}

}  // namespace
}  // namespace chain::testing
