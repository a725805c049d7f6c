// SPDX-License-Identifier: MIT
// The box2d3 engine (Box2D v3), registered only when chainbench is built against an installed v3:
// it rests the built-in stack within the scene's answer, counts the contacts of the large
// pyramid as Box2D's own writing does, gives the same bits on any thread count, and its task pool
// runs every item of a task exactly once.
#include "engines/box2d3_tasks.h"
#include "engines/registry.h"
#include "run/runner.h"
#include "scenes/scene_library.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cstring>
#include <string>
#include <vector>

namespace chainbench {
namespace {

BodyState final_state(const std::string& spec, const Scene& scene, int steps) {
  const auto engine = make_engine(parse_engine_spec(spec), scene);
  for (int k = 0; k < steps; ++k)
    engine->step(k);
  BodyState out(scene.bodies.size());
  engine->read_state(out);
  return out;
}

double contacts(const Engine& engine) {
  const auto defs = engine.counter_defs();
  const auto values = engine.counters();
  for (std::size_t c = 0; c < defs.size() && c < values.size(); ++c) {
    if (defs[c].name == "contacts") return values[c];
  }
  ADD_FAILURE() << "no contacts counter";
  return -1.0;
}

// The 15-box stack, built at rest, stays where it was built within the scene's own tolerance
// (5% of a box), though v3's soft contacts let it sag (docs/box2d3.md measures by how much).
TEST(Box2d3, RestsTheStackWithinTheScenesAnswer) {
  const Scene stack = make_scene("stack", {});
  ASSERT_EQ(stack.bodies.size(), 16u);
  for (const char* spec : {"box2d3", "box2d3:sleep=1", "box2d3:threads=2"}) {
    SCOPED_TRACE(spec);
    const EngineRun run = run_engine(stack, parse_engine_spec(spec), RunOptions{});
    ASSERT_TRUE(run.expect.has_value());
    EXPECT_TRUE(run.expect->pass) << "largest error " << run.expect->max_error << " m";
  }
}

// Continuous collision works as the key says: a crate falling at 200 m/s onto a 0.1 m slab
// (12 times the slab's depth and more than its own size a step) stops on it with ccd on, as the
// scene states (fast_drop: on the slab at y = 0.3, never below), and passes through it with ccd
// off. The pass with ccd on needs v3 to know the body's extent (docs/box2d3.md §2).
TEST(Box2d3, ContinuousCollisionStopsAFastCrateOnAThinSlab) {
  const Scene drop = make_scene("fast_drop", {"speed=200"});
  for (const char* spec : {"box2d3", "box2d3:ccd=2"}) {
    SCOPED_TRACE(spec);
    const EngineRun run = run_engine(drop, parse_engine_spec(spec), RunOptions{});
    ASSERT_TRUE(run.expect.has_value());
    EXPECT_TRUE(run.expect->pass) << "largest error " << run.expect->max_error << " m";
  }
  const BodyState off = final_state("box2d3:ccd=0", drop, drop.steps);
  EXPECT_LT(off.position[1].y, 0.0) << "without continuous collision the crate passes through";
}

// Box2D's large pyramid (base 100, 5,050 boxes) touches 14,950 times: 100 boxes on the ground,
// two boxes below each of the 4,950 above the bottom row, and 4,950 side by side neighbours.
TEST(Box2d3, CountsTheLargePyramidsContacts) {
  const Scene pyramid = make_scene("pyramid", {"base=100"});
  const auto engine = make_engine(parse_engine_spec("box2d3"), pyramid);
  engine->step(0);
  EXPECT_EQ(contacts(*engine), 14'950.0);
  for (int k = 1; k < 60; ++k)
    engine->step(k);
  EXPECT_EQ(contacts(*engine), 14'950.0);
}

// A stack of three boxes touches three times, awake or asleep (asleep by step 120); boxes apart
// touch nothing, however close v3's speculative margin brings them into its contact list.
TEST(Box2d3, CountsEachTouchingPairOnce) {
  const Scene stack = make_scene("stack", {"n=3"});
  for (const char* spec : {"box2d3", "box2d3:sleep=1"}) {
    SCOPED_TRACE(spec);
    const auto engine = make_engine(parse_engine_spec(spec), stack);
    for (int k = 0; k <= 120; ++k) {
      engine->step(k);
      if (k == 0 || k == 120) {
        EXPECT_EQ(contacts(*engine), 3.0) << "step " << k;
      }
    }
  }
  Scene apart;
  apart.name = "apart";
  build::ground(apart, 10.0);
  build::box(apart, "falling", BodyKind::kDynamic, {0.0, 3.0}, {0.5, 0.5});
  const auto engine = make_engine(parse_engine_spec("box2d3"), apart);
  engine->step(0);
  EXPECT_EQ(contacts(*engine), 0.0);
}

// Box2D v3 partitions its work the same way whatever the workers: 1, 2 and 3 threads end a moving
// scene (bodies falling, colliding and sliding) in the very same bits.
TEST(Box2d3, SameBitsOnEveryThreadCount) {
  for (const char* scene : {"rain", "pyramid"}) {
    SCOPED_TRACE(scene);
    const Scene s = make_scene(scene, {});
    const BodyState one = final_state("box2d3", s, 90);
    for (const char* spec : {"box2d3:threads=2", "box2d3:threads=3"}) {
      SCOPED_TRACE(spec);
      const BodyState many = final_state(spec, s, 90);
      ASSERT_EQ(many.position.size(), one.position.size());
      EXPECT_EQ(std::memcmp(many.position.data(), one.position.data(),
                            one.position.size() * sizeof(Vec2d)),
                0);
      EXPECT_EQ(std::memcmp(many.velocity.data(), one.velocity.data(),
                            one.velocity.size() * sizeof(Vec2d)),
                0);
    }
  }
}

// Each item of a parallel-for runs once, in chunks no smaller than asked, on workers below the
// pool's count; tasks in flight together all finish.
TEST(Box2d3, ListsItsSpeedCapAsTheKeySetsIt) {
  const EngineDef& def = engine_def("box2d3");
  ASSERT_EQ(def.limits.size(), 1u);
  EXPECT_EQ(def.limits[0].unit, "m/s");
  const Scene scene = make_scene("stack", {"n=2"});
  EXPECT_EQ(def.limits[0].speed(parse_engine_spec("box2d3"), scene), 400.0);
  EXPECT_EQ(def.limits[0].speed(parse_engine_spec("box2d3:max_speed=50"), scene), 50.0);
}

TEST(Box2d3TaskPool, RunsEveryItemOnceOnItsWorkers) {
  struct Items {
    std::vector<std::atomic<int>> runs;
    std::atomic<int> bad_worker{0};
    std::atomic<int> short_chunk{0};
    int min_range = 1;
    int threads = 1;
    explicit Items(int n) : runs(static_cast<std::size_t>(n)) {}
  };
  auto body = [](int begin, int end, std::uint32_t worker, void* context) {
    Items& items = *static_cast<Items*>(context);
    if (worker >= static_cast<std::uint32_t>(items.threads)) ++items.bad_worker;
    if (end - begin < items.min_range && end != static_cast<int>(items.runs.size()))
      ++items.short_chunk;
    for (int i = begin; i < end; ++i)
      ++items.runs[static_cast<std::size_t>(i)];
  };
  for (const int threads : {1, 2, 4}) {
    SCOPED_TRACE(threads);
    TaskPool pool(threads);
    Items a(1000), b(7);
    a.threads = b.threads = threads;
    a.min_range = 64;
    void* ta = pool.enqueue(+body, 1000, 64, &a);
    void* tb = pool.enqueue(+body, 7, 1, &b);
    pool.finish(tb);
    pool.finish(ta);
    EXPECT_EQ(pool.enqueue(+body, 0, 1, &a), nullptr);
    for (const Items* items : {&a, &b}) {
      for (const auto& n : items->runs)
        EXPECT_EQ(n.load(), 1);
      EXPECT_EQ(items->bad_worker.load(), 0);
      EXPECT_EQ(items->short_chunk.load(), 0);
    }
  }
}

}  // namespace
}  // namespace chainbench
