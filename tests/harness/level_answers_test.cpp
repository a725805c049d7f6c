// SPDX-License-Identifier: MIT
// The level scenes' right answers admit every sound discretisation: an engine that moves as the
// physics says meets them whatever the speed and time step, including a character whose edge
// reaches the ledge exactly at a step and a friction stop shorter than one step's travel.
#include "engines/engine_spec.h"
#include "engines/registry.h"
#include "run/runner.h"
#include "scenes/scene_library.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace chainbench {
namespace {

bool meets(const std::string& engine, const std::string& scene, std::vector<std::string> sets) {
  const Scene s = make_scene(scene, sets);
  const EngineRun r = run_engine(s, parse_engine_spec(engine), RunOptions{});
  return r.expect && r.expect->pass;
}

// 1.25 / (v dt) whole at 3, 5 and 7.5 m/s with dt = 1/60, and at 5 and 12.5 m/s with dt = 0.01:
// there rounding decides in which step support ends. Box2D moves a body at most 2 m per step
// (b2_maxTranslation), so its speeds stay below 2 / dt; at dt = 0.05 that is 40 m/s.
TEST(LevelAnswers, LedgeWalkIsMetAtEverySpeedAndStep) {
  for (const char* dt : {"0.016666666666666666", "0.01", "0.05"}) {
    for (const char* speed : {"0.5", "1", "3", "5", "6", "7.5", "12.5", "25"}) {
      const std::vector<std::string> sets = {std::string("dt=") + dt,
                                             std::string("speed=") + speed};
      for (const char* engine : {"chain", "box2d", "chipmunk"}) {
        SCOPED_TRACE(std::string(engine) + " dt=" + dt + " speed=" + speed);
        EXPECT_TRUE(meets(engine, "ledge_walk", sets));
      }
    }
  }
}

TEST(LevelAnswers, FrictionStopsAreMetWhenTheyTakeLessThanAStep) {
  for (const char* scene : {"rough_slide", "platform_ride"}) {
    for (const char* dt : {"0.016666666666666666", "0.1"}) {
      for (const char* speed : {"1", "2", "10"}) {
        const std::vector<std::string> sets = {std::string("dt=") + dt,
                                               std::string("speed=") + speed, "mu=2"};
        for (const char* engine : {"chain", "box2d", "chipmunk"}) {
          SCOPED_TRACE(std::string(engine) + " " + scene + " dt=" + dt + " speed=" + speed);
          EXPECT_TRUE(meets(engine, scene, sets));
        }
      }
    }
  }
}

// A gap no wider than the box is crossed at the box's speed, and one wider by more than two
// steps' travel is fallen into: the chain solver meets both answers at every speed and step,
// driven or free. The answer can be missed: Box2D stops the default driven box dead at the far
// corner, which its resting sink (up to its 5 mm linear slop) puts in the box's way, and
// Chipmunk snags a slow free box even on a join (gap 0).
TEST(LevelAnswers, GapCrossingIsMetAtEverySpeedAndStep) {
  int crossings = 0, falls = 0;
  for (const char* dt : {"0.016666666666666666", "0.004166666666666667", "0.05"}) {
    for (const char* speed : {"1", "2", "8", "20"}) {
      for (const char* gap : {"0", "0.5", "0.9", "1", "1.6", "3"}) {
        for (const char* driven : {"0", "1"}) {
          const std::vector<std::string> sets = {
              std::string("dt=") + dt, std::string("speed=") + speed, std::string("gap=") + gap,
              std::string("driven=") + driven, "steps=240"};
          const Scene s = make_scene("gap_cross", sets);
          if (s.expect.empty()) continue;  // between the two answers: nothing expected
          const bool cross = std::stod(gap) <= 1.0;
          (cross ? crossings : falls) += 1;
          SCOPED_TRACE(std::string("dt=") + dt + " speed=" + speed + " gap=" + gap +
                       " driven=" + driven);
          EXPECT_TRUE(meets("chain", "gap_cross", sets));
        }
      }
    }
  }
  EXPECT_EQ(crossings, 3 * 4 * 4 * 2);
  EXPECT_GT(falls, 20);
  EXPECT_FALSE(meets("box2d", "gap_cross", {}));
  EXPECT_FALSE(meets("chipmunk", "gap_cross", {"gap=0", "speed=1", "driven=0"}));
}

// A crate set down on a running belt slips v^2 / (2 mu g) and rides at the belt's speed: every
// built-in engine meets it, each through its own conveyor (the chain solver's surface velocity,
// Box2D 2.4's tangent speed set before each contact is solved, Chipmunk's surface velocity, v3's
// tangent speed), at belt speeds either way and two coefficients; and nothing judges the belt's
// work unstable. Plugins, whose ABI carries no belts, are refused by name.
TEST(LevelAnswers, ConveyorsCarryCratesInEveryEngine) {
  int engines = 0;
  for (const EngineDef& def : engine_registry()) {
    if (def.name == "plugin") continue;
    ++engines;
    for (const char* speed : {"2", "-5"}) {
      for (const char* mu : {"0.5", "1"}) {
        const std::vector<std::string> sets = {std::string("speed=") + speed,
                                               std::string("mu=") + mu, "steps=120"};
        const Scene s = make_scene("conveyor", sets);
        ASSERT_EQ(s.expect.size(), 1u);
        const EngineRun r = run_engine(s, parse_engine_spec(def.name), RunOptions{});
        SCOPED_TRACE(def.name + " speed=" + speed + " mu=" + mu);
        ASSERT_TRUE(r.expect && r.verdict);
        EXPECT_TRUE(r.expect->pass);
        EXPECT_EQ(r.verdict->worst, VerdictClass::kOk) << to_string(r.verdict->worst);
      }
    }
  }
  EXPECT_GE(engines, 3);
  // Without friction the belt runs under the crate, and the answer for friction is missed.
  Scene s = make_scene("conveyor", {});
  for (SceneBody& b : s.bodies)
    b.friction = 0.0;
  const EngineRun r = run_engine(s, parse_engine_spec("chain"), RunOptions{});
  ASSERT_TRUE(r.expect);
  EXPECT_FALSE(r.expect->pass);
  const std::string why =
      missing_capability(parse_engine_spec("plugin:path=" CHAINBENCH_RELAXATION_PLUGIN),
                         make_scene("conveyor", {"mu=0"}));
  EXPECT_NE(why.find("has no conveyors"), std::string::npos) << why;
  EXPECT_NE(missing_capability(parse_engine_spec("chain:variant=seed2014"),
                               make_scene("conveyor", {"mu=0"}))
                .find("no conveyors"),
            std::string::npos);
}

// The bound still catches a wrong answer: a frictionless crate on a moving platform stays
// behind, and with friction 1 it must ride.
TEST(LevelAnswers, AFrictionlessRideMissesTheAnswerWithFriction) {
  Scene s = make_scene("platform_ride", {});
  for (SceneBody& b : s.bodies)
    b.friction = 0.0;
  const EngineRun r = run_engine(s, parse_engine_spec("chain"), RunOptions{});
  ASSERT_TRUE(r.expect);
  EXPECT_FALSE(r.expect->pass);
}

}  // namespace
}  // namespace chainbench
