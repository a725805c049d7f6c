// SPDX-License-Identifier: MIT
// The level scenes' right answers admit every sound discretisation: an engine that moves as the
// physics says meets them whatever the speed and time step, including a character whose edge
// reaches the ledge exactly at a step and a friction stop shorter than one step's travel.
#include "engines/engine_spec.h"
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
