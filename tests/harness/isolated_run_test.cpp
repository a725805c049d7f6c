// SPDX-License-Identifier: MIT
// A plugin's run comes back from its child process (isolated_run.h) as bytes: what comes back must
// be the run itself, every field of it, so that no figure, expectation result or verdict of an
// isolated engine differs from what the same engine gives in process. The comparison is
// EngineRun's defaulted operator==, so a field added later and left out of the bytes fails here
// (the scenes below give every field of an expectation result a value other than its default).
#include "run/isolated_run.h"
#include "output/report.h"
#include "run/runner.h"
#include "scenes/scene_file.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace chainbench {
namespace {

const char* const kBallistic = "plugin:path=" CHAINBENCH_TEST_PLUGINS "/libtest_plugin_none.so";

// A box sliding at 1 m/s for 0.5 s (to x = 0.5) with nothing to meet, and what a scene states of
// it: a position met, at_rest missed (m/s), a position missed by 0.005 m beyond its 0.1 m (a
// near miss: within a tenth of the tolerance), and a clear position miss.
Scene sliding(const std::string& expect) {
  return parse_scene(
      R"({"schema":1,"name":"slide","steps":30,"gravity":[0,0],"bodies":[
          {"name":"box","type":"dynamic","center":[0,0],"half_extents":[0.5,0.5],"mass":1,
           "velocity":[1,0]}],"expect":[)" +
          expect + "]}",
      "test");
}

std::vector<Scene> scenes() {
  return {
      sliding(R"({"body":"box","at_rest":0.01},{"body":"box","center":[0.5,0],"tolerance":0.52})"),
      sliding(R"({"body":"box","center":[0.605,0],"tolerance":0.1})"),
      sliding(R"({"body":"box","center":[3,0],"tolerance":0.1})"),
      sliding(R"({"body":"box","center":[0.5,0],"tolerance":0.1})"),
  };
}

TEST(IsolatedRun, TheBytesOfARunReadBackAsTheRunFieldByField) {
  bool near_miss = false, has_speed = false, speed_failed = false, position_passed = false;
  bool staged = false;
  RunOptions options;
  options.stages = true;  // the chain engine times its stages (the plugin times none)
  for (const Scene& s : scenes()) {
    for (const char* engine : {kBallistic, "chain"}) {
      const EngineSpec spec = parse_engine_spec(engine);
      const EngineRun run = run_engine(s, spec, options);
      staged |= !run.stages.empty();
      ASSERT_TRUE(run.expect && run.verdict);
      near_miss |= run.expect->near_miss;
      has_speed |= run.expect->has_speed;
      speed_failed |= !run.expect->speed_pass;
      position_passed |= run.expect->position_pass && run.expect->has_position;
      const EngineRun back = decode_run(s, spec, encode_run(run));
      EXPECT_TRUE(back == run) << engine << " on " << s.expect.size() << " entries";
      EXPECT_EQ(back.verdict->str(), run.verdict->str());
    }
  }
  // The scenes gave the fields whose loss this guards against values other than their defaults.
  EXPECT_TRUE(near_miss);
  EXPECT_TRUE(has_speed);
  EXPECT_TRUE(speed_failed);
  EXPECT_TRUE(position_passed);
  EXPECT_TRUE(staged);
}

// What the parent writes for an engine run in a child is what it writes for the same engine run
// in process, apart from the step times.
nlohmann::ordered_json untimed_json(const Scene& s, const EngineRun& run) {
  RunReport report;
  report.scene = &s;
  report.runs = {run};
  nlohmann::ordered_json j = run_json(report);
  for (auto& e : j["runs"]) {
    e.erase("ms_per_step");
    e.erase("setup_ms");
  }
  return j;
}

TEST(IsolatedRun, AnIsolatedRunWritesTheJsonOfTheRunInProcess) {
  for (const Scene& s : scenes()) {
    const EngineSpec spec = parse_engine_spec(kBallistic);
    RunOptions child;
    child.isolate = true;
    child.timeout_s = 60;
    const EngineRun here = run_engine(s, spec, RunOptions{});
    const EngineRun there = run_engine(s, spec, child);
    ASSERT_FALSE(there.failure) << *there.failure;
    EXPECT_EQ(untimed_json(s, there).dump(1), untimed_json(s, here).dump(1));
    EngineRun retimed = there;
    retimed.timing = here.timing;
    EXPECT_TRUE(retimed == here);
  }
}

}  // namespace
}  // namespace chainbench
