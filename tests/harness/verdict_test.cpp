// SPDX-License-Identifier: MIT
// Verdicts that tell the physical truth, on scene files under tests/scenes/verdicts/ that state
// their analytic answers: each engine is judged right or wrong by physics, never by another
// engine.
#include "output/report.h"
#include "run/runner.h"
#include "scenes/scene_file.h"

#include <gtest/gtest.h>

#include <sstream>
#include <string>

namespace chainbench {
namespace {

Scene scene(const std::string& name) {
  // Appended piece by piece: GCC 12 at -O1 takes the chain of + for an overflow (-Warray-bounds).
  std::string path = CHAINBENCH_TEST_SCENES "/verdicts/";
  path += name;
  path += ".json";
  return load_scene_file(path);
}

EngineRun run(const Scene& s, const char* engine) {
  return run_engine(s, parse_engine_spec(engine), RunOptions{});
}

// Rigid boxes at rest stay put whatever the top one weighs. Box2D 2.4 at 8/3 iterations without
// continuous collision lets a 10,000 kg box sink 0.82 m into the 1 kg one under it and ends with
// the stack 2 m short: wrong and penetrating, where `stress` once printed `ok`.
TEST(Verdicts, HeavyTopStackIsWrongInBox2dAndOkInTheChainSolver) {
  const Scene s = scene("heavy_top_stack");
  const EngineRun box2d = run(s, "box2d:ccd=0");
  ASSERT_TRUE(box2d.verdict.has_value());
  EXPECT_EQ(box2d.verdict->worst, VerdictClass::kWrong) << box2d.verdict->str();
  EXPECT_FALSE(box2d.expect->pass);
  EXPECT_EQ(s.bodies[*box2d.expect->entries[0].body].name, "top");
  EXPECT_GT(box2d.expect->max_error, 1.0);
  EXPECT_GT(box2d.metrics.worst_overlap->depth, 0.5);
  bool penetrating = false;
  for (const Finding& f : box2d.verdict->findings)
    penetrating |= f.what == VerdictClass::kPenetrating;
  EXPECT_TRUE(penetrating);
  for (const char* engine : {"chain", "chain:variant=seed2014"}) {
    const EngineRun chain = run(s, engine);
    EXPECT_TRUE(chain.verdict->ok()) << engine << ": " << chain.verdict->str();
    EXPECT_EQ(chain.expect->max_error, 0.0) << engine;
  }
}

// Four boxes created at one spot on a floor: the 2014 variant pushes two of them down through
// the floor, where they fall for the rest of the run. Stable is no, whatever the scene's width.
TEST(Verdicts, BoxesThroughTheFloorAreNotStable) {
  const Scene s = scene("four_at_one_spot");
  const EngineRun seed = run(s, "chain:variant=seed2014");
  ASSERT_TRUE(seed.stable().has_value());
  EXPECT_FALSE(*seed.stable());
  EXPECT_TRUE(*seed.metrics.tunnelled);
  ASSERT_TRUE(seed.metrics.tunnel.has_value());
  EXPECT_EQ(s.bodies[seed.metrics.tunnel->through].name, "floor");
  EXPECT_EQ(seed.verdict->worst, VerdictClass::kTunnelled) << seed.verdict->str();
  EXPECT_FALSE(seed.expect->pass);  // a box ends below the floor
  // Wider walls around the same fall do not change that (the old bound was 10 scene sizes).
  Scene wide = s;
  wide.bodies[0].half_extents.x = 1000.0;
  EXPECT_FALSE(*run(wide, "chain:variant=seed2014").stable());
  const EngineRun modern = run(s, "chain");
  EXPECT_TRUE(*modern.stable());
  EXPECT_TRUE(modern.verdict->ok()) << modern.verdict->str();
}

// The push train's analytic answer (in the file): every body moves 4.9933333 m. The modern solver
// lands within 3e-6 m of it; Box2D's warm starting throws the front boxes ahead by over a metre.
// The table says which engine meets the expectations and does not blame it for being far from
// the reference.
TEST(Verdicts, PushTrainBlamesTheReferenceNotTheEngineThatIsRight) {
  const Scene s = scene("push_train");
  RunReport report;
  report.scene = &s;
  report.runs.push_back(run(s, "chain"));
  report.runs.push_back(run(s, "box2d"));
  report.reference_spec = parse_engine_spec("box2d");
  compare(report);
  const EngineRun& chain = report.runs[0];
  ASSERT_TRUE(chain.expect.has_value());
  EXPECT_TRUE(chain.expect->pass);
  EXPECT_LT(chain.expect->max_error, 3e-6);
  EXPECT_TRUE(chain.verdict->ok()) << chain.verdict->str();
  const EngineRun& box2d = report.runs[1];
  EXPECT_FALSE(box2d.expect->pass);
  EXPECT_GT(box2d.expect->max_error, 0.5);
  EXPECT_EQ(box2d.verdict->worst, VerdictClass::kWrong);
  std::ostringstream table;
  print_run_table(table, report);
  const std::string text = table.str();
  EXPECT_NE(text.find("expectations (1 entry): met by chain; missed by box2d (ref)"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("note: the reference box2d misses the expectations"), std::string::npos)
      << text;
  EXPECT_NE(text.find("vs ref max m"), std::string::npos) << text;
  EXPECT_EQ(text.find("err max"), std::string::npos) << text;
}

// Under the momentum-less zero rule the bodies' velocities stay 0 while they travel at
// 27 / 3 = 9 m/s: peak speed, measured from positions, says 9.
TEST(Verdicts, PeakSpeedOfAZeroRulePushIsTheSpeedTheBodiesMovedAt) {
  const Scene s = scene("zero_rule_push");
  for (const char* engine : {"chain:velocity=zero", "chain:variant=seed2014"}) {
    const EngineRun r = run(s, engine);
    EXPECT_NEAR(*r.metrics.peak_speed, 9.0, 1e-9) << engine;
    // Box 2 moved 9 m while its velocity read 0 throughout.
    EXPECT_NEAR(r.final_positions[2].x, 2.0 + 9.0, 1e-9) << engine;
  }
  EXPECT_NEAR(*run(s, "chain").metrics.peak_speed, 27.0, 1e-6);
}

// Bounces bound speed by energy: a light box thrown up at three times the fall speed by a heavy
// one is physics, and every engine that gets it right is judged right (no blow-up, stable).
TEST(Verdicts, AnElasticTossIsNotABlowUp) {
  const Scene s = scene("elastic_toss");
  for (const char* engine : {"chain", "box2d", "chipmunk"}) {
    const EngineRun r = run(s, engine);
    EXPECT_GT(*r.metrics.peak_speed, 25.0) << engine;  // the elastic answer is 29.1 m/s
    EXPECT_FALSE(*r.metrics.blow_up) << engine;
    EXPECT_TRUE(*r.stable()) << engine;
    EXPECT_TRUE(r.expect->pass) << engine;
  }
  EXPECT_TRUE(run(s, "chain").verdict->ok());
}

// Two crates meeting at 24 m/s end a step 0.2 m into each other; Box2D pushes them out of it
// within a step, which moves them faster than any speed in the scene. That is a push out of an
// overlap, reported as penetrating, not a blow-up; and all three engines land on the momentum
// answer.
TEST(Verdicts, PushingOutAFreshOverlapIsNotABlowUp) {
  const Scene s = scene("head_on");
  for (const char* engine : {"chain", "box2d", "chipmunk"}) {
    const EngineRun r = run(s, engine);
    EXPECT_FALSE(*r.metrics.blow_up) << engine;
    EXPECT_TRUE(r.expect->pass) << engine << " " << r.expect->max_error;
  }
  const EngineRun box2d = run(s, "box2d");
  EXPECT_GT(*box2d.metrics.peak_speed, 16.0);  // above the 16 m/s bound, within the push-out
  EXPECT_EQ(box2d.verdict->worst, VerdictClass::kPenetrating) << box2d.verdict->str();
}

}  // namespace
}  // namespace chainbench
