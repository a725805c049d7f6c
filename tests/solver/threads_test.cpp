// SPDX-License-Identifier: MIT
// WorldDef::threads spreads the independent parts of a step over worker threads in fixed blocks
// of bodies: every thread count must give the same bits, step after step, whatever the scene
// does. And the count is validated like every other setting.
#include "world_helpers.h"

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <vector>

namespace chain::testing {
namespace {

constexpr double kDt = 1.0 / 60.0;

// A wall of stacks, a kinematic pusher driven into a long row, a rain of rough boxes falling
// onto the wall, and a kinematic lift carrying a stack up and down: over 7,500 bodies, several
// blocks of them for the workers, with pushes, chains, falls, friction and moving immovable
// bodies in every step.
struct MixedScene {
  std::vector<BodyId> ids;
  BodyId pusher, lift;
};

MixedScene build_mixed(World& w) {
  MixedScene s;
  auto add = [&](const BodyDef& d) {
    s.ids.push_back(w.create_body(d));
    return s.ids.back();
  };
  add(static_box(0.0, -1.0, 400.0, 1.0));
  for (int c = 0; c < 200; ++c) {  // the wall: 200 columns of 10
    for (int k = 0; k < 10; ++k)
      add(dynamic_box(-300.0 + c, 0.5 + k));
  }
  // The row: 1,500 boxes, pushed from its left end at 3 m/s.
  s.pusher = add(kinematic_box(-50.5, 0.5, 0.5, 0.5, {3.0, 0.0}));
  for (int i = 0; i < 1500; ++i)
    add(dynamic_box(-49.5 + i * 1.0, 0.5));
  std::uint64_t state = 11;
  for (int i = 0; i < 4000; ++i) {  // the rain: rough boxes of mixed sizes falling onto the wall
    state = state * 6364136223846793005u + 1442695040888963407u;
    const double u = static_cast<double>(state >> 11) * 0x1.0p-53;
    BodyDef d =
        dynamic_box(-300.0 + (i % 200) + 0.3 * u, 12.0 + 1.3 * (i / 200) + u, 0.2 + 0.25 * u);
    d.friction = 0.5;
    d.velocity = {0.5 - u, -2.0 * u};
    add(d);
  }
  s.lift = add(kinematic_box(-350.0, 0.25, 5.0, 0.25, {0.0, 0.0}));
  for (int k = 0; k < 20; ++k)
    add(dynamic_box(-350.0, 1.0 + k, 0.5, 1.0 + k));
  return s;
}

struct Bits {
  std::vector<std::uint64_t> words;
  bool operator==(const Bits&) const = default;
};

Bits run(int threads, int steps) {
  WorldDef def = world_def(Variant::kModern, VelocityRule::kInelastic);
  def.threads = threads;
  World w(def);
  const MixedScene s = build_mixed(w);
  Bits bits;
  for (int step = 0; step < steps; ++step) {
    w.set_drive(s.lift, {0.0, step % 60 < 30 ? 1.0 : -1.0});
    w.step(kDt);
  }
  for (const BodyId id : s.ids) {
    const Vec2 p = w.position(id), v = w.velocity(id);
    for (const double x : {p.x, p.y, v.x, v.y})
      bits.words.push_back(std::bit_cast<std::uint64_t>(x));
    bits.words.push_back(w.touching_flags(id));
  }
  return bits;
}

TEST(Threads, OneTwoAndThreeThreadsGiveTheSameBits) {
  const Bits one = run(1, 90);
  // The scene did move: the pusher went right, the rain fell, the lift carried its stack.
  ASSERT_FALSE(one.words.empty());
  EXPECT_TRUE(run(2, 90) == one);
  EXPECT_TRUE(run(3, 90) == one);
}

TEST(Threads, SceneMovesAndSettles) {
  WorldDef def = world_def(Variant::kModern, VelocityRule::kInelastic);
  def.threads = 2;
  World w(def);
  const MixedScene s = build_mixed(w);
  const Vec2 last_of_row = w.position(s.ids[2002]);
  for (int step = 0; step < 90; ++step) {
    w.set_drive(s.lift, {0.0, step % 60 < 30 ? 1.0 : -1.0});
    w.step(kDt);
  }
  // The pusher drove the row 4.5 m along (3 m/s for 1.5 s); the lift carried its stack.
  EXPECT_NEAR(w.position(s.ids[2002]).x - last_of_row.x, 4.5, 0.05);
  EXPECT_NEAR(w.position(s.ids[2002]).y, 0.5, 1e-9);
  const BodyId top_of_lift_stack = s.ids.back();
  EXPECT_GT(w.position(top_of_lift_stack).y, 20.0);
  // No falling box went through the wall or the floor.
  for (std::size_t k = 3502; k < 7502; ++k)
    EXPECT_GT(w.position(s.ids[k]).y, 0.0) << "box " << k;
}

TEST(Threads, CountIsValidated) {
  WorldDef def;
  def.threads = 0;
  EXPECT_FALSE(validate(def).empty());
  def.threads = kMaxThreads + 1;
  EXPECT_FALSE(validate(def).empty());
  def.threads = kMaxThreads;
  EXPECT_TRUE(validate(def).empty());
}

TEST(Threads, CopiedWorldKeepsItsThreadsAndBits) {
  WorldDef def = world_def(Variant::kModern, VelocityRule::kInelastic);
  def.threads = 3;
  World a(def);
  build_mixed(a);
  a.step(kDt);
  World b = a;
  EXPECT_EQ(b.def().threads, 3);
  a.step(kDt);
  b.step(kDt);
  for (std::uint32_t id = 0; id < a.body_count(); ++id) {
    EXPECT_EQ(std::bit_cast<std::uint64_t>(a.position(BodyId{id}).x),
              std::bit_cast<std::uint64_t>(b.position(BodyId{id}).x));
    EXPECT_EQ(std::bit_cast<std::uint64_t>(a.velocity(BodyId{id}).y),
              std::bit_cast<std::uint64_t>(b.velocity(BodyId{id}).y));
  }
}

}  // namespace
}  // namespace chain::testing
