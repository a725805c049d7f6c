// SPDX-License-Identifier: MIT
// Once warmed up, a step allocates nothing: every buffer keeps its capacity from step to step; and
// a world holds no more than its budget of bytes a body. This executable replaces the global
// operator new to count allocations while a flag is set, and the bytes held at any time.
#include "world_access.h"
#include "world_helpers.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdlib>
#include <functional>
#include <new>
#include <numeric>
#include <random>
#include <vector>

// The replacements below pair malloc with free. GCC inlines them into library code that calls
// operator new/delete and then sees new released by free, which would be a mismatch anywhere else.
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"

namespace {
std::atomic<bool> g_counting{false};
std::atomic<long> g_allocations{0};
// Bytes asked for and not yet released, by every operator new of the program: each block carries
// its size in a header as wide as malloc's alignment, so that the count is the program's requests,
// whatever the allocator rounds them to.
std::atomic<long long> g_held{0};
constexpr std::size_t kHeader = alignof(std::max_align_t);
}  // namespace

void* operator new(std::size_t n) {
  if (g_counting.load(std::memory_order_relaxed))
    g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (auto* p = static_cast<unsigned char*>(std::malloc(n + kHeader))) {
    *reinterpret_cast<std::size_t*>(p) = n;
    g_held.fetch_add(static_cast<long long>(n), std::memory_order_relaxed);
    return p + kHeader;
  }
  throw std::bad_alloc();
}
void* operator new[](std::size_t n) {
  return operator new(n);
}
void operator delete(void* p) noexcept {
  if (!p) return;
  auto* block = static_cast<unsigned char*>(p) - kHeader;
  g_held.fetch_sub(static_cast<long long>(*reinterpret_cast<std::size_t*>(block)),
                   std::memory_order_relaxed);
  std::free(block);
}
void operator delete[](void* p) noexcept {
  operator delete(p);
}
void operator delete(void* p, std::size_t) noexcept {
  operator delete(p);
}
void operator delete[](void* p, std::size_t) noexcept {
  operator delete(p);
}

namespace chain::testing {
namespace {

long allocations_during(World& w, int steps) {
  g_allocations = 0;
  g_counting = true;
  for (int s = 0; s < steps; ++s)
    w.step(1.0 / 60.0);
  g_counting = false;
  return g_allocations;
}

// A pyramid, a driven pusher against a row, a box being crushed by a lift and a falling pile:
// pushes, chains, crushes and velocity groups every step.
void build_busy_scene(World& w) {
  add_floor(w, 100.0);
  for (int row = 0; row < 12; ++row) {
    for (int k = 0; k < 12 - row; ++k) {
      w.create_body(dynamic_box(static_cast<double>(k) - 0.5 * static_cast<double>(11 - row) - 30.0,
                                0.5 + static_cast<double>(row)));
    }
  }
  const BodyId pusher = w.create_body(dynamic_box(0.0, 0.5));
  for (int i = 1; i <= 20; ++i)
    w.create_body(dynamic_box(static_cast<double>(i), 0.5));
  w.set_drive(pusher, {1.0, 0.0});
  w.create_body(dynamic_box(40.0, 0.5));
  w.create_body(kinematic_box(40.0, 1.45, 2.0, 0.5, {0.0, -0.001}));  // squeezing already
}

// A level: a box sliding over flush tiles, a character walking with x held, a box driven fast
// into the floor and another into a box against a wall (swept every step), rough crates carried
// by a platform that goes back and forth.
void build_level_scene(World& w, std::vector<BodyId>& platforms) {
  for (int i = 0; i < 40; ++i)
    w.create_body(static_box(-20.0 + i + 0.5, -0.5, 0.5, 0.5));
  BodyDef slider = dynamic_box(-18.0, 0.25, 0.25);
  slider.velocity = {3.0, 0.0};
  w.create_body(slider);
  const BodyId walker = w.create_body(dynamic_box(-10.0, 0.25, 0.25));
  w.set_drive(walker, {1.0, 0.0}, DriveAxes::kX);
  const BodyId diver = w.create_body(dynamic_box(0.0, 0.25, 0.25));
  w.set_drive(diver, {0.0, -40.0});
  w.create_body(static_box(10.0, 1.0, 0.5, 1.0));
  w.create_body(dynamic_box(9.0, 0.5));
  const BodyId ram = w.create_body(dynamic_box(7.0, 0.5, 0.1));
  w.set_drive(ram, {60.0, 0.0}, DriveAxes::kX);
  const BodyId platform = w.create_body(kinematic_box(-30.0, 2.0, 3.0, 0.5, {0.0, 0.0}));
  BodyDef rough = dynamic_box(-30.0, 2.75, 0.25);
  rough.friction = 1.0;
  w.create_body(rough);
  rough.center.y += 0.5;
  w.create_body(rough);
  platforms.push_back(platform);
}

TEST(Allocation, LevelStepsAllocateNothing) {
  for (const VelocityRule rule : {VelocityRule::kZero, VelocityRule::kInelastic}) {
    World w(world_def(Variant::kModern, rule));
    std::vector<BodyId> platforms;
    build_level_scene(w, platforms);
    BodyDef friction_source = static_box(0.0, -100.0, 1.0, 1.0);
    friction_source.friction = 1.0;
    w.create_body(friction_source);
    for (int s = 0; s < 200; ++s) {
      for (const BodyId p : platforms)
        w.set_drive(p, {s % 40 < 20 ? 2.0 : -2.0, 0.0}, DriveAxes::kX);
      if (s == 60) {
        g_allocations = 0;
        g_counting = true;
      }
      w.step(1.0 / 60.0);
      if (s >= 60) {
        ASSERT_GT(w.last_step_stats().fast_bodies, 0u);
        ASSERT_GT(w.last_step_stats().swept, 0u);
      }
    }
    g_counting = false;
    EXPECT_EQ(g_allocations, 0) << (rule == VelocityRule::kZero ? "zero" : "inelastic");
  }
}

TEST(Allocation, WarmedUpStepsAllocateNothing) {
  for (const Variant v : {Variant::kModern, Variant::kSeed2014}) {
    for (const VelocityRule rule : {VelocityRule::kZero, VelocityRule::kInelastic}) {
      World w(world_def(v, rule));
      build_busy_scene(w);
      allocations_during(w, 30);  // warm-up: buffers reach their working size
      EXPECT_EQ(allocations_during(w, 120), 0) << variant_name(v);
      EXPECT_GT(w.last_step_stats().resolve_calls, 0u);
    }
  }
}

// A wall of 6,000 boxes at rest on its own floor, beside the busy scene.
void add_resting_wall(World& w) {
  w.create_body(static_box(500.0, -1.0, 400.0, 1.0));
  for (int c = 0; c < 600; ++c) {
    for (int k = 0; k < 10; ++k)
      w.create_body(dynamic_box(200.0 + c, 0.5 + k));
  }
}

// With worker threads, the blocks of bodies they take and their notes live in buffers sized
// once: a busy scene with a wall of 6,000 boxes beside it (several blocks) allocates nothing.
TEST(Allocation, ThreadedStepsAllocateNothing) {
  WorldDef def = world_def(Variant::kModern, VelocityRule::kInelastic);
  def.threads = 3;
  def.skip_rest = false;  // the wall rests: left out, it would run no block (next test)
  World w(def);
  build_busy_scene(w);
  add_resting_wall(w);
  allocations_during(w, 30);
  EXPECT_EQ(allocations_during(w, 120), 0);
  EXPECT_GT(w.last_step_stats().resolve_calls, 6000u);
}

// A busy scene beside a resting wall of 6,000 boxes whose islands are left out (islands.h), on
// one thread and on three: waking and leaving out islands allocates nothing once warmed up.
TEST(Allocation, StepsThatLeaveRestingIslandsOutAllocateNothing) {
  for (const int threads : {1, 3}) {
    WorldDef def = world_def(Variant::kModern, VelocityRule::kInelastic);
    def.threads = threads;
    World w(def);
    build_busy_scene(w);
    add_resting_wall(w);
    allocations_during(w, 30);
    EXPECT_EQ(allocations_during(w, 120), 0) << threads << " threads";
    EXPECT_GE(w.last_step_stats().resting, 6000u);
    EXPECT_GT(w.last_step_stats().resolve_calls, 0u);
  }
}

// Columns of boxes, half of them on a lift that goes up and down, whose slots are shuffled every
// 40 steps: the modern solver renumbers them into the order it reaches them in, long after the
// warm-up.
TEST(Allocation, RenumberingTheBodiesAllocatesNothing) {
  World w(world_def(Variant::kModern, VelocityRule::kInelastic));
  add_floor(w, 100.0);
  const BodyId lift = w.create_body(kinematic_box(-10.0, 0.25, 10.0, 0.25, {0.0, 0.0}));
  for (int c = 0; c < 40; ++c) {
    double y = c < 20 ? 0.5 : 0.0;  // the first 20 columns stand on the lift
    for (int k = 0; k < 30; ++k) {
      BodyDef d = dynamic_box(static_cast<double>(c) - 19.5, 0.0);
      d.half_extents.y = 0.3 + 0.01 * static_cast<double>((c * 13 + k * 29) % 40);
      d.center.y = y + d.half_extents.y;
      y += 2.0 * d.half_extents.y;
      w.create_body(d);
    }
  }
  // Chains meet their candidates in slot order, so a world renumbered once in the order its steps
  // reach its bodies keeps that order: every 40 steps the test shuffles the dynamic bodies' slots,
  // as a world whose bodies moved far would have them, and the layout then puts them back in
  // reach order.
  auto& impl = detail::WorldAccess::impl(w);
  w.set_drive(lift, {0.0, 0.5});
  w.step(1.0 / 60.0);  // the bodies take their slots in the first step
  ASSERT_EQ(impl.bodies.dynamic_end, 1200u);
  std::vector<std::uint32_t> shuffled(impl.bodies.size());
  std::iota(shuffled.begin(), shuffled.end(), 0u);
  std::mt19937 rng(99u);
  std::shuffle(shuffled.begin(), shuffled.begin() + impl.bodies.dynamic_end, rng);
  int renumberings = 0;
  for (int s = 1; s < 240; ++s) {
    w.set_drive(lift, {0.0, s % 40 < 20 ? 0.5 : -0.5});
    if (s % 40 == 30) impl.renumber(shuffled);
    if (s == 80) {  // two periods of the lift: every buffer has its working size
      g_allocations = 0;
      g_counting = true;
    }
    w.step(1.0 / 60.0);
    if (s >= 80) renumberings += static_cast<int>(w.last_step_stats().renumbered);
  }
  g_counting = false;
  EXPECT_EQ(g_allocations, 0);
  EXPECT_GT(renumberings, 2);
}

// Bytes a world holds a body, after it has stepped (every buffer at its working size): issue 20's
// budget is 800. Five layouts of about 10,000 bodies, the sizes at which the per-body arrays'
// growth showed most (doubled vectors held up to twice what they needed): a pyramid, a wall of
// columns, a row pushed top-down, a rough pile (friction's buffers), a pile of mixed sizes; each
// stepped with and without skip_rest, and a world with one body created and one destroyed every
// step.
TEST(Memory, AWorldHoldsAtMost800BytesABody) {
  constexpr double kBudget = 800.0;
  struct Layout {
    const char* name;
    Vec2 gravity;
    std::function<int(World&)> build;  // returns the bodies it made
  };
  const std::vector<Layout> layouts = {
      {"pyramid",
       {0.0, -10.0},
       [](World& w) {
         add_floor(w, 200.0);
         int n = 1;
         for (int row = 0; row < 140; ++row) {
           for (int k = 0; k < 140 - row; ++k, ++n)
             w.create_body(dynamic_box(k - 0.5 * (139 - row), 0.5 + row));
         }
         return n;
       }},
      {"wall",
       {0.0, -10.0},
       [](World& w) {
         add_floor(w, 600.0);
         for (int c = 0; c < 1000; ++c) {
           for (int k = 0; k < 10; ++k)
             w.create_body(dynamic_box(1.0 * c - 500.0, 0.5 + k));
         }
         return 10'001;
       }},
      {"pushed row",
       {0.0, 0.0},
       [](World& w) {
         const BodyId pusher = w.create_body(dynamic_box(0.0, 0.0));
         w.set_drive(pusher, {2.0, 0.0});
         for (int i = 1; i <= 10'000; ++i)
           w.create_body(dynamic_box(i, 0.0));
         return 10'001;
       }},
      {"rough pile",
       {0.0, -10.0},
       [](World& w) {
         BodyDef floor = static_box(0.0, -1.0, 200.0, 1.0);
         floor.friction = 0.5;
         w.create_body(floor);
         for (int i = 0; i < 10'000; ++i) {
           BodyDef d = dynamic_box(1.05 * (i % 200) - 105.0, 0.5 + 1.05 * (i / 200));
           d.friction = 0.5;
           w.create_body(d);
         }
         return 10'001;
       }},
      {"mixed pile",
       {0.0, -10.0},
       [](World& w) {
         add_floor(w, 200.0);
         for (int i = 0; i < 10'000; ++i) {
           const double half = 0.2 + 0.05 * (i * 7 % 9);
           w.create_body(dynamic_box(1.2 * (i % 100) - 60.0, 1.2 * (i / 100) + half, half));
         }
         return 10'001;
       }},
  };
  for (const Layout& layout : layouts) {
    for (const bool skip_rest : {true, false}) {
      WorldDef def = world_def(Variant::kModern, VelocityRule::kInelastic, layout.gravity);
      def.skip_rest = skip_rest;
      const long long before = g_held.load();
      {
        World w(def);
        const int bodies = layout.build(w);
        for (int s = 0; s < 45; ++s)
          w.step(1.0 / 60.0);
        const double per_body = static_cast<double>(g_held.load() - before) / bodies;
        EXPECT_LE(per_body, kBudget) << layout.name << (skip_rest ? "" : ", skip_rest off");
        // The count is real: the bodies' own arrays alone hold more than 100 bytes a body.
        EXPECT_GT(per_body, 100.0) << layout.name;
      }
      EXPECT_EQ(g_held.load(), before) << layout.name << ": the world gave back what it held";
    }
  }
  // Churn: a wall of 10,000 boxes, and one box created and one destroyed every step.
  const long long before = g_held.load();
  World w(world_def(Variant::kModern, VelocityRule::kInelastic));
  const int wall = layouts[1].build(w);
  ASSERT_STREQ(layouts[1].name, "wall");
  std::vector<BodyId> dropped;
  for (int s = 0; s < 120; ++s) {
    dropped.push_back(w.create_body(dynamic_box(-550.0, 20.0 + s)));
    if (dropped.size() > 10) {
      w.destroy_body(dropped.front());
      dropped.erase(dropped.begin());
    }
    w.step(1.0 / 60.0);
  }
  EXPECT_LE(static_cast<double>(g_held.load() - before) / (wall + 10), kBudget) << "churn";
}

}  // namespace
}  // namespace chain::testing
