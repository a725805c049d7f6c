// SPDX-License-Identifier: MIT
// Bodies that come and go (SceneBody::from_step, to_step): a scene file whose bodies enter and
// leave runs in every engine that adds and removes bodies with the right answer, a window outside
// a body's life is refused, plugins without CB_CAN_LIFETIMES are refused by name, spawn_rain meets
// its stated answer, and the chain solver's runs with spawns are the same bits twice and on two
// threads.
#include "engines/registry.h"
#include "run/runner.h"
#include "scenes/scene_file.h"
#include "scenes/scene_library.h"
#include "support/input_error.h"

#include <gtest/gtest.h>

#include <string>

namespace chainbench {
namespace {

// "keep" rests on the ground throughout; "late" enters at step 30 0.4 m up and lands; "leaver"
// rests on the ground and leaves after step 39; "heir" enters at step 40 exactly where "leaver"
// rested, which it would overlap by its whole size had the leaver stayed. Tolerances: 5 cm, the
// share of a unit box by which a result is visibly wrong (scene_library.h, kVisible).
const char* const kComings = R"({
  "schema": 1, "name": "comings", "dt": 0.016666666666666666, "steps": 120,
  "bodies": [
    {"name": "ground", "type": "static", "center": [0, -0.5], "half_extents": [10, 0.5]},
    {"name": "keep", "type": "dynamic", "center": [-4, 0.5], "half_extents": [0.5, 0.5], "mass": 1},
    {"name": "late", "type": "dynamic", "center": [0, 0.9], "half_extents": [0.5, 0.5], "mass": 1,
     "from_step": 30},
    {"name": "leaver", "type": "dynamic", "center": [4, 0.5], "half_extents": [0.5, 0.5],
     "mass": 1, "to_step": 40},
    {"name": "heir", "type": "dynamic", "center": [4, 0.5], "half_extents": [0.5, 0.5], "mass": 1,
     "from_step": 40}
  ],
  "expect": [
    {"body": "keep", "center": [-4, 0.5], "tolerance": 0.05},
    {"body": "late", "center": [0, 0.9], "tolerance": 0.001, "from_step": 30, "to_step": 30},
    {"body": "late", "center": [0, 0.5], "tolerance": 0.05, "from_step": 80},
    {"body": "leaver", "center": [4, 0.5], "tolerance": 0.05, "from_step": 0, "to_step": 40},
    {"body": "heir", "center": [4, 0.5], "tolerance": 0.05, "from_step": 40},
    {"body": "*", "min": [null, 0.45], "from_step": 0}
  ]
})";

// kComings with its first `from` replaced by `to`.
std::string edited(const std::string& from, const std::string& to) {
  std::string s = kComings;
  const std::size_t at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) s.replace(at, from.size(), to);
  return s;
}

TEST(Lifetimes, SceneFileBodiesComeAndGoInEveryEngine) {
  const Scene scene = parse_scene(kComings, "comings.json");
  ASSERT_TRUE(scene.has_lifetimes());
  int engines = 0;
  for (const EngineDef& def : engine_registry()) {
    const EngineSpec spec = parse_engine_spec(def.name == "plugin" ? "chain" : def.name);
    if (def.name == "plugin") continue;  // needs its library: plugin_test.cpp, and below
    SCOPED_TRACE(def.name);
    ++engines;
    const EngineRun run = run_engine(scene, spec, RunOptions{});
    ASSERT_TRUE(run.expect.has_value());
    for (const ExpectOutcome& o : run.expect->entries) {
      EXPECT_TRUE(o.pass) << "expect[" << o.index << "] error " << o.error << " at state "
                          << o.state;
    }
    // The heir is in the leaver's place from its first state: nothing pushed it out of one.
    EXPECT_NEAR(run.final_positions[4].y, 0.5, 0.05);
  }
  EXPECT_GE(engines, 3);  // chain, box2d, chipmunk (and box2d3 where it is built)
}

TEST(Lifetimes, AWindowOutsideABodysLifeIsRefusedNamingTheEntry) {
  const std::string text = edited(R"("from_step": 80})", R"("from_step": 10})");  // enters at 30
  try {
    parse_scene(text, "comings.json");
    FAIL() << "a window before the body entered was accepted";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("comings.json: expect[2].from_step"), std::string::npos) << what;
    EXPECT_NE(what.find("outside the life of body \"late\""), std::string::npos) << what;
  }
  // An unwindowed entry is checked on the final state, after the leaver left.
  const std::string final_state = edited(R"(, "from_step": 0, "to_step": 40})", "}");
  try {
    parse_scene(final_state, "comings.json");
    FAIL() << "a final-state entry on a body gone by then was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(
        std::string(e.what()).find("expect[3]: checks the final state, 120, outside the life"),
        std::string::npos)
        << e.what();
  }
}

// The body a relation names beside its own must be there too: "keep below leaver" on the final
// state judges a body gone since step 40.
TEST(Lifetimes, ARelationToABodyOutOfTheWorldIsRefused) {
  for (const auto& [entry, field] :
       {std::pair<std::string, std::string>{
            R"({"body": "keep", "below": "leaver", "tolerance": 2})",
            "expect[6]: checks the final state"},
        {R"({"body": "keep", "on": "late", "tolerance": 2, "from_step": 0})",
         "expect[6].from_step"},
        {R"({"body": "late", "above": "heir", "tolerance": 2, "from_step": 30})",
         "expect[6].from_step"}}) {
    SCOPED_TRACE(entry);
    const std::string text = edited(R"("from_step": 0}
  ])",
                                    R"("from_step": 0}, )" + entry + "\n  ]");
    try {
      parse_scene(text, "comings.json");
      FAIL() << "a relation to a body out of the world was accepted";
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("comings.json: " + field), std::string::npos) << what;
      EXPECT_NE(what.find("outside the life of body"), std::string::npos) << what;
    }
  }
  // Within both lives it is a fact like any other: "heir" on "ground" from its first state.
  const std::string fine = edited(
      R"("from_step": 0}
  ])",
      R"("from_step": 0}, {"body": "heir", "on": "ground", "tolerance": 0.05, "from_step": 40}
  ])");
  const Scene scene = parse_scene(fine, "comings.json");
  const EngineRun run = run_engine(scene, parse_engine_spec("chain"), RunOptions{});
  ASSERT_TRUE(run.expect.has_value());
  EXPECT_TRUE(run.expect->pass) << run.expect->max_error;
}

// A squeeze counts only the walls in the world in the state judged: walls that left at step 10
// squeeze nothing at the end, so "squeezed" fails there, and holds while they stand.
TEST(Lifetimes, ASqueezeCountsOnlyTheWallsInTheWorld) {
  auto scene_with = [](const std::string& window) {
    return parse_scene(R"({
      "schema": 1, "name": "walls_leave", "steps": 60, "gravity": [0, 0],
      "bodies": [
        {"name": "left", "type": "static", "center": [-1, 0], "half_extents": [0.5, 2],
         "to_step": 10},
        {"name": "right", "type": "static", "center": [1, 0], "half_extents": [0.5, 2],
         "to_step": 10},
        {"name": "box", "type": "dynamic", "center": [0, 0], "half_extents": [0.5, 0.5], "mass": 1}
      ],
      "expect": [{"body": "box", "squeezed": true, "tolerance": 0.01)" +
                           window + R"(}]
    })",
                       "walls_leave.json");
  };
  const Scene standing = scene_with(R"(, "from_step": 0, "to_step": 10)");
  const Scene gone = scene_with("");
  const EngineSpec chain = parse_engine_spec("chain");
  const EngineRun held = run_engine(standing, chain, RunOptions{});
  ASSERT_TRUE(held.expect.has_value());
  EXPECT_TRUE(held.expect->pass) << held.expect->max_error;
  const EngineRun after = run_engine(gone, chain, RunOptions{});
  ASSERT_TRUE(after.expect.has_value());
  EXPECT_FALSE(after.expect->pass) << "walls gone since step 10 still squeeze at step 60";
}

// Two bodies entering together, overlapping as the file places them, start overlapping as bodies
// of state 0 do: in every engine, also those that hold positions in single precision, they are
// not penetrating for it (0.3 m deep in a scene whose tolerance is the starting overlap).
TEST(Lifetimes, BodiesEnteringTogetherOverlappingAreJudgedAsStartingSo) {
  const Scene scene = parse_scene(R"({
    "schema": 1, "name": "enter_pair", "steps": 60,
    "bodies": [
      {"name": "ground", "type": "static", "center": [0, -0.5], "half_extents": [10, 0.5]},
      {"name": "a", "type": "dynamic", "center": [0, 0.5], "half_extents": [0.5, 0.5],
       "mass": 1, "from_step": 20},
      {"name": "b", "type": "dynamic", "center": [0.7, 0.5], "half_extents": [0.5, 0.5],
       "mass": 1, "from_step": 20}
    ]
  })",
                                  "enter_pair.json");
  for (const EngineDef& def : engine_registry()) {
    if (def.name == "plugin") continue;
    SCOPED_TRACE(def.name);
    const EngineSpec spec = parse_engine_spec(def.name);
    if (!missing_capability(spec, scene).empty()) continue;
    const EngineRun run = run_engine(scene, spec, RunOptions{});
    ASSERT_TRUE(run.verdict.has_value());
    EXPECT_TRUE(run.verdict->ok()) << run.verdict->str();
    // The deepest penetration is what the engine left after a step, not the 0.3 m the file placed
    // them in: every engine pushes them apart some in the step after they enter, chain at once.
    ASSERT_TRUE(run.metrics.max_penetration.has_value());
    EXPECT_LT(*run.metrics.max_penetration, 0.3);
    if (def.name == "chain") {
      EXPECT_EQ(*run.metrics.max_penetration, 0.0);
    }
  }
}

TEST(Lifetimes, ABodyMustTakePartInAStep) {
  const std::string text = edited(R"("to_step": 40},)", R"("to_step": 0},)");
  try {
    parse_scene(text, "comings.json");
    FAIL() << "a body with no step was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("bodies[3].to_step: must be > from_step"),
              std::string::npos)
        << e.what();
  }
}

// The relaxation example has no add_body or remove_body (no CB_CAN_LIFETIMES).
TEST(Lifetimes, PluginsAreRefusedByName) {
  const Scene scene = parse_scene(kComings, "comings.json");
  const EngineSpec spec = parse_engine_spec("plugin:path=" CHAINBENCH_RELAXATION_PLUGIN);
  const std::string why = missing_capability(spec, scene);
  EXPECT_NE(why.find("cannot add or remove bodies"), std::string::npos) << why;
  EXPECT_NE(why.find("late"), std::string::npos) << why;
  EXPECT_THROW(make_engine(spec, scene), InputError);
}

TEST(Lifetimes, SpawnRainMeetsItsAnswer) {
  const Scene scene = make_scene("spawn_rain", {});
  ASSERT_TRUE(validate(scene).empty());
  ASSERT_TRUE(scene.has_lifetimes());
  for (const char* engine : {"chain", "box2d"}) {
    SCOPED_TRACE(engine);
    const EngineRun run = run_engine(scene, parse_engine_spec(engine), RunOptions{});
    ASSERT_TRUE(run.expect.has_value());
    for (const ExpectOutcome& o : run.expect->entries) {
      EXPECT_TRUE(o.pass) << "expect[" << o.index << "] on "
                          << scene.bodies[o.body.value_or(0)].name << ": error " << o.error
                          << " at state " << o.state << ", at (" << o.position.x << ", "
                          << o.position.y << ")";
    }
  }
}

TEST(Lifetimes, SpawnRainStatesEveryBoxsRestAndScales) {
  const Scene small = make_scene("spawn_rain", {});
  std::size_t landed = 0;
  for (const Expectation& e : small.expect)
    landed += e.kind == Expectation::Kind::kCenter;
  // 12 waves of 10 slots x 3 boxes enter in 120 steps, each for 60 steps: the 8 that are seen
  // for 46 steps or more (the fall of the top box, 1.5 m, and 10 steps) are stated at rest.
  EXPECT_EQ(small.bodies.size(), 60u + 12u * 30u);
  EXPECT_EQ(landed, 8u * 30u);
  const Scene large = make_scene("spawn_rain", {"cols=100"});
  EXPECT_EQ(large.bodies.size(), 600u + 12u * 300u);
}

// churn: per_step boxes take part in each step and no other, so every step but the first
// creates and destroys that many; the wall never moves, in chain and in Box2D.
TEST(Lifetimes, ChurnCreatesAndDestroysPerStepBoxesAndLeavesTheWallAlone) {
  const Scene scene = make_scene("churn", {"cols=20", "height=3", "per_step=2", "steps=30"});
  ASSERT_TRUE(validate(scene).empty());
  const std::size_t wall = 20u * 3u + 1u;
  ASSERT_EQ(scene.bodies.size(), wall + 2u * 30u);
  for (int k = 0; k < 30; ++k) {
    std::size_t taking_part = 0;
    for (const SceneBody& b : scene.bodies)
      taking_part += b.from_step <= k && k < b.to_step;
    EXPECT_EQ(taking_part, wall + 2u) << "step " << k;
  }
  for (const char* engine : {"chain", "box2d"}) {
    SCOPED_TRACE(engine);
    const EngineRun run = run_engine(scene, parse_engine_spec(engine), RunOptions{});
    ASSERT_TRUE(run.expect.has_value());
    EXPECT_TRUE(run.expect->pass);
  }
  // Nothing comes or goes with per_step=0: the same wall, still.
  EXPECT_FALSE(make_scene("churn", {"per_step=0"}).has_lifetimes());
}

TEST(Lifetimes, ChainWithSpawnsIsTheSameBitsTwiceAndOnTwoThreads) {
  const Scene scene = make_scene("spawn_rain", {"cols=40", "steps=90"});
  const EngineRun a = run_engine(scene, parse_engine_spec("chain"), RunOptions{});
  const EngineRun b = run_engine(scene, parse_engine_spec("chain"), RunOptions{});
  const EngineRun two = run_engine(scene, parse_engine_spec("chain:threads=2"), RunOptions{});
  EXPECT_EQ(a.hash, b.hash);
  EXPECT_EQ(a.hash, two.hash);
  ASSERT_TRUE(a.expect.has_value());
  EXPECT_TRUE(a.expect->pass);
}

}  // namespace
}  // namespace chainbench
