// SPDX-License-Identifier: MIT
// `chainbench run --profile`: each engine's own timing of its step's stages, printed after the
// table and written to the JSON as stages_ms, over the same steps as ms_per_step.
#include "cli_run.h"

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <vector>

namespace {

using cli::chainbench;
using cli::Result;

std::string temp(const std::string& name) {
  return ::testing::TempDir() + "chainbench_profile_" + name;
}

nlohmann::ordered_json read_json(const std::string& path) {
  std::ifstream in(path);
  return nlohmann::ordered_json::parse(in);
}

const nlohmann::ordered_json& run_of(const nlohmann::ordered_json& j,
                                     const std::string& engine_prefix) {
  for (const auto& r : j.at("runs")) {
    if (r.at("engine").get<std::string>().rfind(engine_prefix, 0) == 0) return r;
  }
  throw std::runtime_error("no run of " + engine_prefix);
}

TEST(CliProfile, EachEnginesStagesArePrintedAndWrittenWithinItsStep) {
  const std::string json = temp("stages.json");
  const Result r = chainbench(
      "run --scene pyramid --set base=10 --steps 30 --engines "
      "chain,box2d,chipmunk --reference none --profile --json " +
      json);
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("stages (each engine's own timing"), std::string::npos) << r.out;
  const nlohmann::ordered_json j = read_json(json);
  const std::vector<std::pair<std::string, std::vector<std::string>>> expected = {
      {"chain:",
       {"prepare", "integrate", "continuous", "contacts", "chains", "velocity", "friction", "layout"}},
      {"box2d:", {"collide", "solve", "solve_toi"}}};
  for (const auto& [engine, names] : expected) {
    const nlohmann::ordered_json& run = run_of(j, engine);
    const nlohmann::ordered_json& stages = run.at("stages_ms");
    std::vector<std::string> keys;
    double sum = 0.0;
    for (const auto& [name, ms] : stages.items()) {
      keys.push_back(name);
      EXPECT_GE(ms.get<double>(), 0.0) << engine << name;
      sum += ms.get<double>();
    }
    EXPECT_EQ(keys, names) << engine;
    // The stages happen inside the timed step, so their means fit in its mean (Box2D's own
    // timer is a float: a relative 1e-6 of slack for its rounding).
    EXPECT_LE(sum, run.at("ms_per_step").at("mean").get<double>() * (1.0 + 1e-6)) << engine;
    for (const std::string& name : names)
      EXPECT_NE(r.out.find(name), std::string::npos) << name;
  }
  // Chipmunk times no stages: it has none in the JSON, and no table, but a line that says so.
  EXPECT_FALSE(run_of(j, "chipmunk:").contains("stages_ms"));
  EXPECT_EQ(r.out.find("\nchipmunk:\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("no stage timing of their own: chipmunk"), std::string::npos) << r.out;
}

TEST(CliProfile, WithoutTheFlagNothingIsTimedByStage) {
  const std::string json = temp("none.json");
  const Result r =
      chainbench("run --scene stack --steps 5 --engines chain --reference none --json " + json);
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_EQ(r.out.find("stages ("), std::string::npos) << r.out;
  EXPECT_FALSE(read_json(json).at("runs").at(0).contains("stages_ms"));
}

}  // namespace
