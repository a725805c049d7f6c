// SPDX-License-Identifier: MIT
// Collision filtering in every engine and in the judges: bodies that do not collide pass through
// each other in every built-in engine, and the judges never call that penetrating, tunnelled or
// escaped; a plugin (whose ABI carries no filter bits) is refused such a scene by name.
#include "engines/registry.h"
#include "judge/engine_run.h"
#include "run/runner.h"
#include "scenes/scene_file.h"
#include "scenes/scene_library.h"
#include "support/input_error.h"

#include <gtest/gtest.h>

#include <string>

namespace chainbench {
namespace {

// A box whose mask leaves out the floor's category falls through it for 2 s (20.2 m by
// semi-implicit Euler, within a step's fall of 0.33 m for the other integrators); a second box,
// which collides with the floor, rests on it; a third, in the first one's category and
// weightless, is built inside the second and stays there, 0.5 m deep in it.
const char* kGhosts = R"({"schema": 1, "name": "ghosts", "steps": 120, "bodies": [
  {"name": "floor", "type": "static", "center": [0, -0.5], "half_extents": [10, 0.5]},
  {"name": "ghost", "type": "dynamic", "center": [-3, 0.5], "half_extents": [0.5, 0.5], "mass": 1,
   "category_bits": 2, "mask_bits": 2},
  {"name": "lander", "type": "dynamic", "center": [3, 0.5], "half_extents": [0.5, 0.5], "mass": 1,
   "mask_bits": 65533},
  {"name": "inside", "type": "dynamic", "center": [3, 0.5], "half_extents": [0.25, 0.25], "mass": 1,
   "category_bits": 2, "mask_bits": 2, "gravity_scale": 0}],
  "expect": [
    {"body": "ghost", "center": [-3, -19.66666666666667], "tolerance": 0.5},
    {"body": "lander", "center": [3, 0.5], "tolerance": 0.05},
    {"body": "inside", "center": [3, 0.5], "tolerance": 1e-6}]})";

TEST(FilterJudging, EveryEngineLetsWhatDoesNotCollidePassAndNoJudgeBlamesIt) {
  const Scene scene = parse_scene(kGhosts, "ghosts.json");
  int engines = 0;
  for (const EngineDef& def : engine_registry()) {
    if (def.name == "plugin") continue;  // refused: below
    SCOPED_TRACE(def.name);
    ++engines;
    const EngineRun run = run_engine(scene, parse_engine_spec(def.name), RunOptions{});
    ASSERT_TRUE(run.expect.has_value());
    for (const ExpectOutcome& o : run.expect->entries)
      EXPECT_TRUE(o.pass) << "expect[" << o.index << "] error " << o.error;
    ASSERT_TRUE(run.verdict.has_value());
    EXPECT_EQ(run.verdict->worst, VerdictClass::kOk) << to_string(run.verdict->worst);
    ASSERT_TRUE(run.metrics.tunnelled.has_value());
    EXPECT_FALSE(*run.metrics.tunnelled);
    EXPECT_TRUE(run.metrics.escaped.empty());
    ASSERT_TRUE(run.metrics.max_penetration.has_value());
    EXPECT_LT(*run.metrics.max_penetration, 0.1);  // resting contacts only; the ghosts sit 0.5 m deep
  }
  EXPECT_GE(engines, 3);  // chain, box2d, chipmunk (and box2d3 where it is built)
}

// The same scene with the filters taken off is judged as it is: the boxes meet.
TEST(FilterJudging, WithoutTheFiltersTheSameBoxesCollide) {
  Scene scene = parse_scene(kGhosts, "ghosts.json");
  for (SceneBody& b : scene.bodies)
    b.category_bits = 1, b.mask_bits = 0xFFFF;
  const EngineRun run = run_engine(scene, parse_engine_spec("chain"), RunOptions{});
  ASSERT_TRUE(run.expect.has_value());
  EXPECT_FALSE(run.expect->pass);
}

TEST(FilterJudging, PluginsAreRefusedByName) {
  const Scene scene = parse_scene(kGhosts, "ghosts.json");
  const EngineSpec spec = parse_engine_spec("plugin:path=" CHAINBENCH_RELAXATION_PLUGIN);
  const std::string why = missing_capability(spec, scene);
  EXPECT_NE(why.find("cannot filter collisions"), std::string::npos) << why;
  EXPECT_NE(why.find("ghost"), std::string::npos) << why;
  EXPECT_THROW(make_engine(spec, scene), InputError);
}

TEST(FilterJudging, FilterWalkIsMetByTheChainSolver) {
  for (const char* speed : {"0.5", "2", "8", "20"}) {
    const Scene s = make_scene("filter_walk", {std::string("speed=") + speed});
    const EngineRun r = run_engine(s, parse_engine_spec("chain"), RunOptions{});
    ASSERT_TRUE(r.expect && r.verdict) << speed;
    EXPECT_TRUE(r.expect->pass) << speed;
    EXPECT_EQ(r.verdict->worst, VerdictClass::kOk) << speed;
  }
}

}  // namespace
}  // namespace chainbench
