// SPDX-License-Identifier: MIT
// Bodies created and destroyed while a modern world runs: a destroyed dynamic body leaves its slot
// empty and a body created later takes it, without the canonical re-sort (world.cpp). What must
// hold whatever the order of the calls: the same bits for every order of the creates and of the
// destroys between two steps and for every thread count; an empty slot overlaps nothing; a body
// created into one collides as any other; read_all() lists every body once; and the cases that
// fall back to the re-sort (larger bodies, static bodies) stay right.
#include "world_helpers.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <set>
#include <utility>
#include <vector>

namespace chain::testing {
namespace {

constexpr double kDt = 1.0 / 60.0;

bool same_bits(Vec2 a, Vec2 b) {
  return std::bit_cast<std::uint64_t>(a.x) == std::bit_cast<std::uint64_t>(b.x) &&
         std::bit_cast<std::uint64_t>(a.y) == std::bit_cast<std::uint64_t>(b.y);
}

// A pile of columns on a floor, stepped until it rests; then for `rounds` steps, before each step,
// `per_step` of the oldest dynamic bodies are destroyed and as many boxes are dropped onto the pile
// (overlapping nothing), the destroys and the creates each in the order `order` gives (0: as
// listed, 1: reversed, 2: rotated by one). Returns every surviving body's final centre, by the
// index of its definition.
std::vector<Vec2> churned_pile(int order, int threads, int rounds = 40, int per_step = 3) {
  WorldDef def = world_def(Variant::kModern, VelocityRule::kInelastic);
  def.threads = threads;
  World w(def);
  add_floor(w, 40.0);
  std::vector<BodyId> ids;
  for (int c = 0; c < 24; ++c) {
    for (int r = 0; r < 5; ++r)
      ids.push_back(w.create_body(dynamic_box(c - 11.5, 0.5 + r)));
  }
  for (int s = 0; s < 20; ++s)
    w.step(kDt);
  auto arrange = [order](std::vector<std::size_t> v) {
    if (order == 1) std::reverse(v.begin(), v.end());
    if (order == 2 && !v.empty()) std::rotate(v.begin(), v.begin() + 1, v.end());
    return v;
  };
  std::size_t oldest = 0;
  for (int s = 0; s < rounds; ++s) {
    std::vector<std::size_t> gone, born;
    for (int k = 0; k < per_step; ++k)
      gone.push_back(oldest++);
    for (const std::size_t i : arrange(gone))
      w.destroy_body(ids[i]);
    for (int k = 0; k < per_step; ++k)
      born.push_back(ids.size() + k);
    ids.resize(ids.size() + per_step);
    for (const std::size_t i : arrange(born)) {
      // Dropped from 1 m above the pile's top, in a column chosen by the step, 3 m apart.
      const double x = ((s * per_step + static_cast<int>(i)) % 8) * 3.0 - 10.5;
      ids[i] = w.create_body(dynamic_box(x, 6.5 + 0.01 * (i % 3)));
    }
    w.step(kDt);
  }
  for (int s = 0; s < 60; ++s)
    w.step(kDt);
  std::vector<Vec2> out(ids.size(), Vec2{0.0, 0.0});
  for (std::size_t i = oldest; i < ids.size(); ++i)
    out[i] = w.position(ids[i]);
  return out;
}

TEST(Churn, EveryOrderOfCreatesAndDestroysAndEveryThreadCountGivesTheSameBits) {
  const std::vector<Vec2> reference = churned_pile(0, 1);
  for (const auto& [order, threads] :
       {std::pair{1, 1}, std::pair{2, 1}, std::pair{0, 2}, std::pair{1, 3}, std::pair{2, 8}}) {
    const std::vector<Vec2> other = churned_pile(order, threads);
    ASSERT_EQ(other.size(), reference.size());
    for (std::size_t i = 0; i < reference.size(); ++i) {
      EXPECT_TRUE(same_bits(reference[i], other[i]))
          << "body " << i << ", order " << order << ", threads " << threads;
    }
  }
}

// Two boxes stacked on the floor; the lower one is destroyed: the upper one falls through the
// space it left onto the floor (a metre's fall at 10 m/s^2 takes under half a second) and rests
// with its bottom on the floor's top, y = 0.5. The empty slot stops nothing.
// A world that steps before it holds any body, and again once its only body is gone: every step
// is a valid empty step, and a body created into it falls freely. The modern resolver took a
// broadphase never configured (generation 0) for one whose near pairs it had scanned (its marker
// started at 0) and read near lists that did not exist (a scene file whose one body enters at
// step 1 crashed `chainbench run`). After k steps of dt from rest, a free body has fallen
// g dt^2 k (k + 1) / 2 (velocity first, then position, each step).
TEST(Churn, AnEmptyWorldStepsAndABodyCreatedInItFallsFreely) {
  for (const Variant v : {Variant::kModern, Variant::kSeed2014}) {
    for (const int threads : {1, 2}) {
      for (const bool skip_rest : {true, false}) {
        WorldDef def = world_def(v, VelocityRule::kInelastic);
        def.threads = threads;
        def.skip_rest = skip_rest;
        World w(def);
        for (int s = 0; s < 3; ++s) {
          w.step(kDt);
          EXPECT_EQ(w.last_step_stats().contacts, 0u);
        }
        const BodyId box = w.create_body(dynamic_box(0.0, 10.0));
        constexpr int kSteps = 20;
        for (int s = 0; s < kSteps; ++s)
          w.step(kDt);
        EXPECT_NEAR(w.position(box).y, 10.0 - 10.0 * kDt * kDt * kSteps * (kSteps + 1) / 2.0, 1e-9)
            << variant_name(v) << ", " << threads << " threads";
        w.destroy_body(box);
        for (int s = 0; s < 3; ++s)
          w.step(kDt);
        EXPECT_EQ(w.body_count(), 0u);
      }
    }
  }
}

TEST(Churn, ABodyFallsThroughTheSpaceADestroyedOneLeft) {
  World w(world_def(Variant::kModern, VelocityRule::kInelastic));
  add_floor(w);
  const BodyId lower = w.create_body(dynamic_box(0.0, 0.5));
  const BodyId upper = w.create_body(dynamic_box(0.0, 1.5));
  for (int s = 0; s < 10; ++s)
    w.step(kDt);
  ASSERT_NEAR(w.position(upper).y, 1.5, 1e-9);
  w.destroy_body(lower);
  EXPECT_FALSE(w.contains(lower));
  EXPECT_EQ(w.body_count(), 2u);
  for (int s = 0; s < 60; ++s)
    w.step(kDt);
  EXPECT_NEAR(w.position(upper).y, 0.5, 1e-9);
  EXPECT_EQ(w.position(upper).x, 0.0);
  EXPECT_EQ(w.velocity(upper).y, 0.0);
}

// Boxes created after others were destroyed (so into their empty slots) land on the floor or on
// each other and rest at exact heights: one dropped on the floor at y = 0.5, one dropped on a
// resting box at y = 1.5; one created 0.3 m deep in a resting box (moving too little to be filed
// again by its own motion) is pushed out on top of it, y = 1.5; and a box thrown down at 300 m/s
// onto a 5 cm slab stops on it (continuous collision sees it), at y = 0.05 + 0.5. No body is fast
// until the throw, so that nothing builds the grid anew and the created bodies are found as filed
// again.
TEST(Churn, BodiesCreatedIntoEmptySlotsCollideAsAnyOther) {
  World w(world_def(Variant::kModern, VelocityRule::kInelastic));
  add_floor(w, 300.0);
  // A row at rest far off: enough bodies that the few created do not send the world to a new
  // scan of its near pairs, so that they are found as bodies filed again are.
  for (int k = 0; k < 200; ++k)
    w.create_body(dynamic_box(40.0 + 1.5 * k, 0.5));
  w.create_body(static_box(20.0, 0.025, 2.0, 0.025));  // the slab, top at 0.05
  const BodyId resting = w.create_body(dynamic_box(12.0, 0.5));
  std::vector<BodyId> first;
  for (int k = 0; k < 6; ++k)
    first.push_back(w.create_body(dynamic_box(-10.0 + 2.0 * k, 0.5)));
  for (int s = 0; s < 5; ++s)
    w.step(kDt);
  for (const BodyId id : first)
    w.destroy_body(id);
  w.step(kDt);
  EXPECT_EQ(w.body_count(), 203u);
  const BodyId inside = w.create_body(dynamic_box(12.0, 1.2));
  const BodyId on_floor = w.create_body(dynamic_box(3.0, 2.0));
  const BodyId base = w.create_body(dynamic_box(6.0, 0.5));
  const BodyId on_base = w.create_body(dynamic_box(6.0, 3.0));
  EXPECT_EQ(w.body_count(), 207u);
  for (int s = 0; s < 90; ++s)
    w.step(kDt);
  EXPECT_NEAR(w.position(on_floor).y, 0.5, 1e-9);
  EXPECT_NEAR(w.position(base).y, 0.5, 1e-9);
  EXPECT_NEAR(w.position(on_base).y, 1.5, 1e-9);
  EXPECT_NEAR(w.position(resting).y, 0.5, 1e-9);
  EXPECT_NEAR(w.position(inside).y, 1.5, 1e-9);
  // Thrown down at 300 m/s into an empty slot, onto the slab: continuous collision stops it there.
  w.destroy_body(on_floor);
  BodyDef thrown = dynamic_box(20.0, 8.0);
  thrown.velocity = {0.0, -300.0};
  const BodyId bullet = w.create_body(thrown);
  for (int s = 0; s < 30; ++s)
    w.step(kDt);
  EXPECT_NEAR(w.position(bullet).y, 0.55, 1e-9);
}

// read_all() lists every body once, its entries as position() and velocity() give them, and
// update_all() keeps a copy of it in step, through destroys, creates and renumberings.
TEST(Churn, ReadAllListsEveryBodyOnceThroughCreatesAndDestroys) {
  World w(world_def(Variant::kModern, VelocityRule::kInelastic));
  add_floor(w);
  std::vector<BodyId> alive;
  for (int k = 0; k < 40; ++k)
    alive.push_back(w.create_body(dynamic_box(-20.0 + k, 0.5 + (k % 3))));
  std::vector<BodyId> ids;
  std::vector<Vec2> pos, vel;
  std::vector<std::uint32_t> changed;
  for (int s = 0; s < 80; ++s) {
    if (s % 3 == 0) {
      w.destroy_body(alive.front());
      alive.erase(alive.begin());
      alive.push_back(w.create_body(dynamic_box(-20.0 + (s % 40), 9.0)));
    }
    w.step(kDt);
    const std::size_t n = w.body_count();
    ASSERT_EQ(n, alive.size() + 1);
    if (s % 3 == 0 || ids.size() != n) {
      ids.assign(n, BodyId{}), pos.assign(n, Vec2{}), vel.assign(n, Vec2{});
      w.read_all(ids, pos, vel);
    } else {
      w.update_all(ids, pos, vel, changed);
    }
    std::set<std::uint32_t> seen;
    for (std::size_t k = 0; k < n; ++k) {
      ASSERT_TRUE(w.contains(ids[k]));
      EXPECT_TRUE(seen.insert(ids[k].value).second) << "id " << ids[k].value << " twice";
      EXPECT_TRUE(same_bits(pos[k], w.position(ids[k])));
      EXPECT_TRUE(same_bits(vel[k], w.velocity(ids[k])));
    }
  }
}

// A created body larger than any the world holds, a static one, and a destroyed static one each
// take the canonical re-sort instead of an empty slot: the results stay right (the big box lands
// on the floor at y = 2, the small box on the new ledge at 1.5 + 0.5).
TEST(Churn, WhatAnEmptySlotCannotTakeFallsBackToTheResort) {
  World w(world_def(Variant::kModern, VelocityRule::kInelastic));
  add_floor(w);
  const BodyId old_ledge = w.create_body(static_box(10.0, 3.0, 1.0, 0.5));
  std::vector<BodyId> boxes;
  for (int k = 0; k < 4; ++k)
    boxes.push_back(w.create_body(dynamic_box(-5.0 + 2.0 * k, 0.5)));
  for (int s = 0; s < 5; ++s)
    w.step(kDt);
  w.destroy_body(boxes[0]);
  const BodyId big = w.create_body(dynamic_box(-30.0, 6.0, 2.0));
  w.destroy_body(old_ledge);
  w.create_body(static_box(20.0, 0.5, 1.0, 1.0));  // a ledge with its top at 1.5
  const BodyId on_ledge = w.create_body(dynamic_box(20.0, 4.0));
  for (int s = 0; s < 90; ++s)
    w.step(kDt);
  EXPECT_EQ(w.body_count(), 7u);
  EXPECT_NEAR(w.position(big).y, 2.0, 1e-9);
  EXPECT_NEAR(w.position(on_ledge).y, 2.0, 1e-9);
  for (std::size_t k = 1; k < boxes.size(); ++k)
    EXPECT_NEAR(w.position(boxes[k]).y, 0.5, 1e-9) << "box " << k;
}

// A world copied with empty slots in it continues as the original does, bit for bit.
TEST(Churn, ACopyWithEmptySlotsContinuesIdentically) {
  World w(world_def(Variant::kModern, VelocityRule::kInelastic));
  add_floor(w);
  std::vector<BodyId> ids;
  for (int k = 0; k < 30; ++k)
    ids.push_back(w.create_body(dynamic_box(-15.0 + k, 0.5 + 2.0 * (k % 4))));
  for (int s = 0; s < 10; ++s)
    w.step(kDt);
  for (int k = 0; k < 30; k += 3)
    w.destroy_body(ids[k]);
  World copy = w;
  for (World* world : {&w, &copy}) {
    world->create_body(dynamic_box(0.3, 12.0));
    for (int s = 0; s < 60; ++s)
      world->step(kDt);
  }
  for (int k = 0; k < 30; ++k) {
    if (k % 3 == 0) continue;
    EXPECT_TRUE(same_bits(w.position(ids[k]), copy.position(ids[k]))) << "body " << k;
  }
}

}  // namespace
}  // namespace chain::testing
