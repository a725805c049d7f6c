// SPDX-License-Identifier: MIT
// Collision filtering (BodyDef::category_bits, mask_bits; Box2D's rule): two bodies collide when
// each one's category is in the other's mask. Bodies that do not collide pass through each other
// as if the other were not there; those that do behave as without filtering.
#include "world_helpers.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace chain::testing {
namespace {

constexpr double kDt = 1.0 / 60.0;

BodyDef filtered(BodyDef d, std::uint16_t category, std::uint16_t mask) {
  d.category_bits = category;
  d.mask_bits = mask;
  return d;
}

WorldDef def_of(Variant v) {
  return world_def(v, v == Variant::kModern ? VelocityRule::kInelastic : VelocityRule::kZero);
}

// A box whose mask leaves out the floor's category falls through it as through nothing: after
// n steps it has fallen g dt^2 n (n + 1) / 2 (semi-implicit Euler), in both variants; one whose
// category the floor's mask leaves out falls through it too.
TEST(Filter, ABoxTheFloorDoesNotCollideWithFallsThroughIt) {
  for (const Variant v : {Variant::kModern, Variant::kSeed2014}) {
    for (const bool by_floor : {false, true}) {
      World w(def_of(v));
      BodyDef floor = static_box(0.0, -1.0, 50.0, 1.0);
      BodyDef box = dynamic_box(0.0, 0.5);
      if (by_floor) {
        floor = filtered(floor, 0x0001, 0xFFFF & ~0x0002);
        box = filtered(box, 0x0002, 0xFFFF);
      } else {
        box = filtered(box, 0x0002, 0xFFFF & ~0x0001);
      }
      w.create_body(floor);
      const BodyId id = w.create_body(box);
      for (int s = 0; s < 60; ++s)
        w.step(kDt);
      EXPECT_NEAR(w.position(id).y, 0.5 - 10.0 * kDt * kDt * 60 * 61 / 2.0, 1e-9)
          << variant_name(v) << by_floor;
      EXPECT_EQ(w.touching_flags(id), 0) << variant_name(v);
    }
  }
}

// Continuous collision and carrying filter too: a box thrown at 100 m/s at a thin wall it does
// not collide with flies on through it (x = v t, top-down), while one that collides stops
// against it; a rising lift it does not collide with leaves a box on the floor.
TEST(Filter, FastBodiesAndLiftsPassWhatTheyDoNotCollideWith) {
  for (const bool collide : {false, true}) {
    World w(world_def(Variant::kModern, VelocityRule::kZero, {0.0, 0.0}));
    w.create_body(filtered(static_box(5.0, 0.0, 0.05, 2.0), 0x0001, collide ? 0xFFFF : 0xFFFD));
    BodyDef d = filtered(dynamic_box(0.0, 0.0, 0.1), 0x0002, 0xFFFF);
    d.velocity = {100.0, 0.0};
    const BodyId box = w.create_body(d);
    for (int s = 0; s < 6; ++s)
      w.step(kDt);
    EXPECT_NEAR(w.position(box).x, collide ? 5.0 - 0.15 : 100.0 * 6 * kDt, 1e-9) << collide;
  }
  World w(world_def(Variant::kModern, VelocityRule::kInelastic));
  add_floor(w);
  w.create_body(filtered(kinematic_box(0.0, -0.25, 2.0, 0.25, {0.0, 1.0}), 0x0004, 0xFFFE));
  const BodyId rider = w.create_body(dynamic_box(0.0, 0.5));
  for (int s = 0; s < 60; ++s)
    w.step(kDt);
  EXPECT_NEAR(w.position(rider).y, 0.5, 1e-9);
}

// Two stacks of five built in the same place, each colliding with the floor and itself but not
// with the other: both rest exactly where they were built, never pushed apart.
TEST(Filter, TwoStacksThatDoNotCollideRestInsideEachOther) {
  for (const Variant v : {Variant::kModern, Variant::kSeed2014}) {
    World w(def_of(v));
    add_floor(w);
    std::vector<BodyId> ids;
    for (int i = 0; i < 5; ++i) {
      ids.push_back(w.create_body(filtered(dynamic_box(0.0, 0.5 + i), 0x0002, 0x0003)));
      ids.push_back(w.create_body(filtered(dynamic_box(0.3, 0.5 + i), 0x0004, 0x0005)));
    }
    for (int s = 0; s < 120; ++s)
      w.step(kDt);
    for (int i = 0; i < 5; ++i) {
      EXPECT_NEAR(w.position(ids[2 * i]).x, 0.0, 1e-9) << variant_name(v);
      EXPECT_NEAR(w.position(ids[2 * i]).y, 0.5 + i, 1e-9) << variant_name(v);
      EXPECT_NEAR(w.position(ids[2 * i + 1]).x, 0.3, 1e-9) << variant_name(v);
      EXPECT_NEAR(w.position(ids[2 * i + 1]).y, 0.5 + i, 1e-9) << variant_name(v);
    }
  }
}

// Boxes of three groups rain onto a floor and shelves that collide with all of them; each group
// collides with itself only. Where no step's order can couple the groups (2014's variant, which
// resolves body by body), every group ends where the same group alone ends, to the bit. The
// modern variant orders a step's work over all its bodies at once (its budget, its walls' layers
// and its renumbering span the world), so there a group's bits may differ; what must hold is that
// no two bodies that collide end inside each other, while bodies of different groups do.
TEST(Filter, GroupsThatDoNotCollideMoveAsIfAlone) {
  for (const Variant v : {Variant::kModern, Variant::kSeed2014}) {
    int crossed = 0;
    for (std::uint32_t seed = 1; seed <= 4; ++seed) {
      struct Made {
        BodyDef def;
        int group;  // -1: the floor and shelves
      };
      std::vector<Made> made;
      made.push_back({static_box(0.0, -1.0, 12.0, 1.0), -1});
      made.push_back({static_box(-4.0, 3.0, 2.0, 0.1), -1});
      made.push_back({static_box(4.0, 5.0, 2.0, 0.1), -1});
      std::mt19937 rng(seed);
      std::uniform_real_distribution<double> unit(0.0, 1.0);
      for (int i = 0; i < 60; ++i) {
        const int group = i % 3;
        const auto bit = static_cast<std::uint16_t>(2u << group);
        BodyDef d = filtered(dynamic_box(-8.0 + 16.0 * unit(rng), 1.0 + 10.0 * unit(rng),
                                         0.2 + 0.3 * unit(rng), 1.0 + unit(rng)),
                             bit, static_cast<std::uint16_t>(bit | 1u));
        d.velocity = {4.0 * (unit(rng) - 0.5), 0.0};
        made.push_back({d, group});
      }
      auto run = [&](int only, std::vector<BodyId>& ids, World& w) {
        for (const Made& m : made)
          ids.push_back(m.group == only || m.group < 0 || only < 0 ? w.create_body(m.def)
                                                                   : BodyId{});
        for (int s = 0; s < 150; ++s)
          w.step(kDt);
      };
      World all(def_of(v));
      std::vector<BodyId> all_ids;
      run(-1, all_ids, all);
      if (v == Variant::kSeed2014) {
        for (int group = 0; group < 3; ++group) {
          World alone(def_of(v));
          std::vector<BodyId> ids;
          run(group, ids, alone);
          for (std::size_t k = 0; k < made.size(); ++k) {
            if (made[k].group != group) continue;
            EXPECT_EQ(bits(all.position(all_ids[k]).x), bits(alone.position(ids[k]).x))
                << "seed " << seed << " body " << k;
            EXPECT_EQ(bits(all.position(all_ids[k]).y), bits(alone.position(ids[k]).y))
                << "seed " << seed << " body " << k;
          }
        }
      }
      for (std::size_t i = 0; i < made.size(); ++i) {
        for (std::size_t j = i + 1; j < made.size(); ++j) {
          const Vec2 a = all.position(all_ids[i]), b = all.position(all_ids[j]);
          const Vec2 ha = made[i].def.half_extents, hb = made[j].def.half_extents;
          const double ox = ha.x + hb.x - std::abs(a.x - b.x);
          const double oy = ha.y + hb.y - std::abs(a.y - b.y);
          const bool inside = ox > 1e-6 && oy > 1e-6;
          if (made[i].group >= 0 && made[j].group >= 0 && made[i].group != made[j].group) {
            crossed += inside;
          } else if (v == Variant::kModern) {
            EXPECT_FALSE(inside) << "seed " << seed << " bodies " << i << " " << j;
          }
        }
      }
    }
    EXPECT_GT(crossed, 10) << variant_name(v);  // the groups did pile through each other
  }
}

// Three rows of ten boxes, each of its own group, built in the same place on a top-down table:
// one pushed by a driven pusher at 2 m/s, one by a pusher at 1 m/s, one left alone. Each ends
// where it ends alone (to rounding), and as the momentum-sharing push says.
TEST(Filter, PushedRowsThatDoNotCollideEachEndAsAlone) {
  auto build = [](World& w, int only, std::vector<BodyId>& ids) {
    for (int group = 0; group < 3; ++group) {
      const auto bit = static_cast<std::uint16_t>(1u << group);
      const bool made = only < 0 || only == group;
      if (group < 2) {
        const BodyId pusher =
            made ? w.create_body(filtered(dynamic_box(0.0, 0.0), bit, bit)) : BodyId{};
        if (made) w.set_drive(pusher, {2.0 - group, 0.0});
        ids.push_back(pusher);
      }
      for (int i = 1; i <= 10; ++i)
        ids.push_back(made ? w.create_body(filtered(dynamic_box(i, 0.0), bit, bit)) : BodyId{});
    }
  };
  World all(world_def(Variant::kModern, VelocityRule::kInelastic, {0.0, 0.0}));
  std::vector<BodyId> all_ids;
  build(all, -1, all_ids);
  for (int s = 0; s < 120; ++s)
    all.step(kDt);
  for (int group = 0; group < 3; ++group) {
    World alone(world_def(Variant::kModern, VelocityRule::kInelastic, {0.0, 0.0}));
    std::vector<BodyId> ids;
    build(alone, group, ids);
    for (int s = 0; s < 120; ++s)
      alone.step(kDt);
    for (std::size_t k = 0; k < ids.size(); ++k) {
      if (!alone.contains(ids[k])) continue;
      EXPECT_NEAR(all.position(all_ids[k]).x, alone.position(ids[k]).x, 1e-9) << group << " " << k;
      EXPECT_NEAR(all.position(all_ids[k]).y, alone.position(ids[k]).y, 1e-9) << group << " " << k;
    }
  }
  ASSERT_EQ(all_ids.size(), 32u);
  EXPECT_NEAR(all.position(all_ids[31]).x, 10.0, 1e-12);  // the row left alone stays
  // 10 kg of row behind a 1 kg pusher at 2 m/s: d = v dt (n - 10 (1 - (10/11)^n)), n = 120.
  const double r = 10.0 / 11.0;
  const double d = 2.0 * kDt * (120 - 10.0 * (1.0 - std::pow(r, 120)));
  EXPECT_NEAR(all.position(all_ids[10]).x, 10.0 + d, 1e-6);
}

}  // namespace
}  // namespace chain::testing
