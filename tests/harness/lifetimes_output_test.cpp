// SPDX-License-Identifier: MIT
// What a run shows of bodies that come and go: the run JSON gives no final position for a body
// out of the world at the end (null) and carries each body's from_step/to_step; the trace has a
// body's rows only while it is in the world and a row with empty values when it leaves; the
// replay page carries the lives it draws bodies by and stores nothing for a body out of the
// world; and spawn_rain's verdicts, with every metric on, are physically true in every engine.
#include "engines/registry.h"
#include "output/position_stream.h"
#include "output/replay_page.h"
#include "output/replay_recorder.h"
#include "output/report.h"
#include "output/trace_writer.h"
#include "run/runner.h"
#include "scenes/scene_file.h"
#include "scenes/scene_library.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace chainbench {
namespace {

// "keep" rests on the ground; "late" enters at step 30 (state 30) 0.4 m up and lands; "leaver"
// rests on the ground until it leaves after step 39 (its last state is 40).
const char* const kScene = R"({
  "schema": 1, "name": "goings", "dt": 0.016666666666666666, "steps": 60,
  "bodies": [
    {"name": "ground", "type": "static", "center": [0, -0.5], "half_extents": [10, 0.5]},
    {"name": "keep", "type": "dynamic", "center": [-4, 0.5], "half_extents": [0.5, 0.5], "mass": 1},
    {"name": "late", "type": "dynamic", "center": [0, 0.9], "half_extents": [0.5, 0.5], "mass": 1,
     "from_step": 30},
    {"name": "leaver", "type": "dynamic", "center": [4, 0.5], "half_extents": [0.5, 0.5],
     "mass": 1, "to_step": 40}
  ]
})";

TEST(LifetimesOutput, TheRunJsonGivesNoPositionForABodyGoneAndCarriesTheLives) {
  const Scene scene = parse_scene(kScene, "goings.json");
  RunReport report;
  report.scene = &scene;
  report.runs.push_back(run_engine(scene, parse_engine_spec("chain"), RunOptions{}));
  const nlohmann::json j = nlohmann::json::parse(run_json(report).dump());
  const nlohmann::json& final = j["runs"][0]["final_positions"];
  ASSERT_EQ(final.size(), 4u);
  EXPECT_TRUE(final[3].is_null()) << final[3];  // the leaver left after step 39
  ASSERT_TRUE(final[2].is_array());             // late is there at the end, landed
  EXPECT_NEAR(final[2][1].get<double>(), 0.5, 0.05);
  EXPECT_EQ(j["scene"]["from_step"], nlohmann::json({0, 0, 30, 0}));
  EXPECT_EQ(j["scene"]["to_step"], nlohmann::json::parse("[null, null, null, 40]"));
  // Metrics are measured and judge the run: the landing of "late" is no blow-up, its entry no
  // tunnelling.
  const nlohmann::json& m = j["runs"][0]["metrics"];
  EXPECT_EQ(m["blow_up"], false);
  EXPECT_EQ(m["tunnelled"], false);
  EXPECT_EQ(j["runs"][0]["verdict"]["class"], "ok") << j["runs"][0]["verdict"];
}

// Parses the trace's rows into body -> [(step, empty values)].
std::map<std::string, std::vector<std::pair<int, bool>>> trace_rows(const std::string& text) {
  std::map<std::string, std::vector<std::pair<int, bool>>> rows;
  std::istringstream in(text);
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> f;
    std::stringstream fields(line);
    for (std::string v; std::getline(fields, v, ',');)
      f.push_back(v);
    if (line.back() == ',') f.emplace_back();
    EXPECT_EQ(f.size(), 10u) << line;
    if (f.size() != 10u) continue;
    rows[f[2]].emplace_back(std::stoi(f[1]), f[3].empty());
  }
  return rows;
}

TEST(LifetimesOutput, TheSparseTraceShowsABodyOnlyWhileItIsInTheWorld) {
  const Scene scene = parse_scene(kScene, "goings.json");
  std::ostringstream out;
  TraceWriter trace(out, scene, TraceFormat::kSparse);
  RunOptions options;
  options.observers.push_back(&trace);
  run_engine(scene, parse_engine_spec("chain"), options);
  const std::string text = out.str();
  EXPECT_NE(text.find("# bodies come and go"), std::string::npos);
  const auto rows = trace_rows(text);
  // late: its first row at the state it enters in, values in every row.
  ASSERT_TRUE(rows.count("late"));
  EXPECT_EQ(rows.at("late").front().first, 30);
  for (const auto& [step, empty] : rows.at("late"))
    EXPECT_FALSE(empty) << step;
  EXPECT_GT(rows.at("late").size(), 5u);  // it falls: a row each step until it rests
  // leaver: a row at step 1 (at rest afterwards), then one with empty values at state 41, the
  // first it is not in, and nothing after.
  ASSERT_TRUE(rows.count("leaver"));
  const auto& leaver = rows.at("leaver");
  EXPECT_EQ(leaver.front(), std::make_pair(1, false));
  EXPECT_EQ(leaver.back(), std::make_pair(41, true));
  for (std::size_t k = 0; k + 1 < leaver.size(); ++k)
    EXPECT_FALSE(leaver[k].second);
  // keep: never gone.
  for (const auto& [step, empty] : rows.at("keep"))
    EXPECT_FALSE(empty) << step;
}

// The dense trace: a row for every body in the world at every step, and none for a body out of
// it (no empty rows: a row is a state); the sidecar says so.
TEST(LifetimesOutput, TheDenseTraceHasARowForEveryBodyInTheWorldAtEveryStep) {
  const Scene scene = parse_scene(kScene, "goings.json");
  std::ostringstream out;
  TraceWriter trace(out, scene);
  RunOptions options;
  options.observers.push_back(&trace);
  run_engine(scene, parse_engine_spec("chain"), options);
  trace.finished();
  std::istringstream in(out.str());
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "engine,step,time,body,x,y,vx,vy,angle,displacement,penetration");
  std::map<std::string, std::vector<int>> steps;
  while (std::getline(in, line)) {
    ASSERT_NE(line[0], '#') << "a comment in the dense form";
    std::vector<std::string> f;
    std::stringstream fields(line);
    for (std::string v; std::getline(fields, v, ',');)
      f.push_back(v);
    ASSERT_EQ(f.size(), 11u) << line;
    EXPECT_EQ(std::stod(f[2]), std::stoi(f[1]) * scene.dt) << line;  // time = step * dt
    steps[f[3]].push_back(std::stoi(f[1]));
  }
  auto range = [](int from, int to) {
    std::vector<int> v;
    for (int k = from; k <= to; ++k)
      v.push_back(k);
    return v;
  };
  EXPECT_EQ(steps["ground"], range(1, 60));
  EXPECT_EQ(steps["keep"], range(1, 60));
  EXPECT_EQ(steps["late"], range(30, 60));   // from the state it enters in
  EXPECT_EQ(steps["leaver"], range(1, 40));  // to_step 40: in state 40, not after
  const nlohmann::json meta =
      nlohmann::json::parse(trace_metadata_json(scene, trace.finished_engines(), false).dump());
  EXPECT_EQ(meta["schema"], "chainbench.trace/1");
  EXPECT_EQ(meta["rows"], "one per engine, step and body in the world at that step");
  EXPECT_EQ(meta["scene"]["dt"], scene.dt);
  ASSERT_EQ(meta["engines"].size(), 1u);
  EXPECT_EQ(meta["engines"][0]["spec"], parse_engine_spec("chain").str());
  EXPECT_EQ(meta["columns"].size(), 11u);
}

TEST(LifetimesOutput, TheReplayPageCarriesTheLivesAndStoresNothingForAnAbsentBody) {
  const Scene scene = parse_scene(kScene, "goings.json");
  ReplayRecorder recorder(scene, std::nullopt);
  RunOptions options;
  options.observers.push_back(&recorder);
  RunReport report;
  report.scene = &scene;
  report.runs.push_back(run_engine(scene, parse_engine_spec("chain"), options));
  std::ostringstream out;
  ReplayPageOptions page;
  page.generator = "test";
  write_replay_page(out, report, recorder, page);
  const std::string html = out.str();
  const std::string open = "<script type=\"application/json\" id=\"replay-data\">";
  const std::size_t from = html.find(open), to = html.find("</script>", from);
  ASSERT_NE(from, std::string::npos);
  const nlohmann::json data =
      nlohmann::json::parse(html.substr(from + open.size(), to - from - open.size()));
  EXPECT_EQ(data["scene"]["lives"]["from"], nlohmann::json({0, 0, 30, 0}));
  EXPECT_EQ(data["scene"]["lives"]["to"], nlohmann::json::parse("[null, null, null, 40]"));
  // The leaver is not among the final centres; late is (it landed).
  const nlohmann::json& final = data["engines"][0]["final"]["bodies"];
  EXPECT_EQ(std::find(final.begin(), final.end(), 3), final.end()) << final;
  EXPECT_NE(std::find(final.begin(), final.end(), 2), final.end()) << final;
  // Stored centres (offsets from the centre as built): late's is 0 until it enters (no move from
  // wherever the engine's state left it), the leaver's where it was last once it left.
  const auto states = PositionStream::decode(recorder.tracks()[0].positions.bytes(), 4);
  ASSERT_EQ(states.size(), 61u);
  for (int k = 0; k < 30; ++k) {
    EXPECT_EQ(states[k][2].x, 0) << k;
    EXPECT_EQ(states[k][2].y, 0) << k;
  }
  EXPECT_LT(states[60][2].y, 0);  // landed
  for (int k = 41; k <= 60; ++k) {
    EXPECT_EQ(states[k][3].x, states[40][3].x) << k;
    EXPECT_EQ(states[k][3].y, states[40][3].y) << k;
    EXPECT_FALSE(states[k][3].lost) << k;
  }
}

// spawn_rain with every metric on: no entering wave reads as a teleport (blow-up), a pass
// through another box (tunnelling) or an overlap with the wave that just left its slots.
TEST(LifetimesOutput, SpawnRainVerdictsArePhysicallyTrueInEveryEngine) {
  const Scene scene = make_scene("spawn_rain", {});
  for (const EngineDef& def : engine_registry()) {
    if (def.name == "plugin") continue;
    SCOPED_TRACE(def.name);
    const EngineRun run = run_engine(scene, parse_engine_spec(def.name), RunOptions{});
    ASSERT_TRUE(run.metrics_computed);
    EXPECT_TRUE(*run.metrics.finite);
    EXPECT_FALSE(*run.metrics.blow_up);
    EXPECT_FALSE(*run.metrics.tunnelled);
    EXPECT_TRUE(*run.metrics.in_bounds);
    // The fastest box is one landing from the top of a slot: sqrt(2 g h), h = 1.5 m, and a step
    // of rounding (no entry counts as a move).
    EXPECT_LT(*run.metrics.peak_speed, std::sqrt(2.0 * 10.0 * 1.5) + 10.0 * scene.dt + 0.1);
    // Boxes land at most a step's fall deep (scene comment, spawn_rain.cpp): within tolerance.
    ASSERT_TRUE(run.verdict.has_value());
    EXPECT_EQ(std::string(to_string(run.verdict->worst)), "ok") << run.verdict->str();
  }
}

}  // namespace
}  // namespace chainbench
