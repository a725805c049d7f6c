// The stress matrix and its verdicts: every case builds, the groups the issue names are all
// there, and the child-process verdicts see tunnelling, errors and hangs for what they are.
#include "stress.h"
#include "scene_library.h"

#include <gtest/gtest.h>

#include <set>
#include <string>

namespace chainbench {
namespace {

TEST(StressMatrix, EveryCaseBuildsItsScene) {
  for (const StressCase& c : stress_cases()) {
    SCOPED_TRACE(c.label());
    const Scene scene = make_scene(c.scene, c.sets);
    EXPECT_FALSE(scene.bodies.empty());
    if (c.probe >= 0) {
      ASSERT_LT(static_cast<std::size_t>(c.probe), scene.bodies.size());
      ASSERT_LT(static_cast<std::size_t>(c.target), scene.bodies.size());
      EXPECT_EQ(scene.bodies[static_cast<std::size_t>(c.probe)].name, "projectile");
    }
  }
}

TEST(StressMatrix, QuickSubsetCoversEveryGroupOfTheFullMatrix) {
  std::set<std::string> all, quick;
  for (const StressCase& c : stress_cases()) {
    all.insert(c.group);
    if (c.quick) quick.insert(c.group);
  }
  EXPECT_EQ(quick, all);
  for (const char* group :
       {"mass ratio, 3-box stack", "mass ratio, push chain", "tall stack",
        "long push chain into a wall", "tiny boxes", "huge boxes", "far from the origin",
        "time step", "fast body", "deep overlap", "squeeze"}) {
    EXPECT_EQ(all.count(group), 1u) << group;
  }
}

StressCase projectile_at(const char* speed) {
  return {"fast body", "projectile", {std::string("speed=") + speed}, false, 7, 3};
}

// At 10 m/s the projectile knocks the middle box out and follows it past the stack: no tunnelling.
TEST(StressVerdicts, SlowProjectileHitsTheStack) {
  const StressVerdict v = run_stress_case(projectile_at("10"), parse_engine_spec("chain"), 60.0);
  ASSERT_TRUE(v.finished);
  EXPECT_FALSE(v.tunnelled);
  EXPECT_EQ(v.verdict(), "ok");
}

// At 500 m/s (8.3 m a step) the projectile jumps the 1 m stack in one step. Box2D, without
// continuous collision between moving bodies, tunnels; the modern chain solver sweeps a fast body
// against the other bodies' motion (solver/src/sweep.h), so the projectile hits the middle box and
// knocks it out of the stack instead. The catcher keeps everything in bounds.
TEST(StressVerdicts, FastProjectileTunnelsInBox2dButNotInChain) {
  for (const char* engine : {"chain", "box2d"}) {
    SCOPED_TRACE(engine);
    const StressVerdict v = run_stress_case(projectile_at("500"), parse_engine_spec(engine), 60.0);
    ASSERT_TRUE(v.finished);
    EXPECT_EQ(v.tunnelled, std::string(engine) == "box2d");
    EXPECT_TRUE(v.in_bounds);
    EXPECT_FALSE(v.fatal());
  }
}

TEST(StressVerdicts, FailureInTheChildIsAnError) {
  const StressCase broken{"none", "stack", {"n=1e12"}, false, -1, -1};
  const StressVerdict v = run_stress_case(broken, parse_engine_spec("chain"), 60.0);
  ASSERT_TRUE(v.finished);
  EXPECT_EQ(v.verdict(), "error");
  EXPECT_NE(v.error.find("out of range"), std::string::npos) << v.error;
  EXPECT_TRUE(v.fatal());
}

// 5,000 overlapping boxes cannot be built and stepped 300 times in 10 ms: the child is killed.
TEST(StressVerdicts, CaseOverItsTimeIsAHang) {
  const StressCase slow{"deep overlap", "overlapping_pile", {"n=5000"}, false, -1, -1};
  const StressVerdict v = run_stress_case(slow, parse_engine_spec("chain"), 0.01);
  EXPECT_TRUE(v.hang);
  EXPECT_FALSE(v.finished);
  EXPECT_EQ(v.verdict(), "hang");
  EXPECT_TRUE(v.fatal());
}

}  // namespace
}  // namespace chainbench
