// SPDX-License-Identifier: MIT
// Shards and merging: which units a part runs, and how parts join (or are refused).
#include "campaign/merge.h"
#include "campaign/shard.h"
#include "support/input_error.h"

#include <gtest/gtest.h>

namespace chainbench {
namespace {

using nlohmann::ordered_json;

TEST(Shard, PartsTakeEveryNthUnitAndTogetherTakeEachOnce) {
  const Shard first = parse_shard("1/3"), third = parse_shard("3/3");
  EXPECT_TRUE(first.has(0));
  EXPECT_TRUE(first.has(3));
  EXPECT_FALSE(first.has(2));
  EXPECT_TRUE(third.has(2));
  for (std::size_t u = 0; u < 20; ++u) {
    int owners = 0;
    for (int k = 1; k <= 3; ++k)
      owners += parse_shard(std::to_string(k) + "/3").has(u);
    EXPECT_EQ(owners, 1) << u;
  }
  for (const char* bad : {"0/3", "4/3", "3", "1/0", "a/b", "1/3x", "-1/3", ""})
    EXPECT_THROW(parse_shard(bad), InputError) << bad;
}

// A sweep part of one scene: its points (ms/step, rms error) and the units they are.
ShardPart sweep_part(int index, const std::vector<std::pair<double, double>>& points,
                     const std::vector<std::size_t>& units, const std::string& grid = "g1",
                     const std::string& version = "1.0") {
  ordered_json list = ordered_json::array();
  for (const auto& [ms, rms] : points) {
    list.push_back({{"engine", "e"},
                    {"ms_per_step", ms},
                    {"ms_spread", 0.0},
                    {"final_position_error", {{"max", rms}, {"rms", rms}}},
                    {"verdict", "ok"},
                    {"pareto", true}});
  }
  ordered_json j = {{"schema", "chainbench.sweep/1"},
                    {"scenes",
                     {{{"scene", {{"name", "s"}}},
                       {"reference", "expect"},
                       {"interrupted", false},
                       {"points", list}}}}};
  j["shard"] = {{"command", "sweep"}, {"version", version}, {"grid", grid}, {"index", index},
                {"count", 2},         {"units", 4},         {"ran", units}};
  return {"part" + std::to_string(index) + ".json", j};
}

TEST(Merge, PutsPointsInGridOrderAndMarksTheParetoFrontOverTheWhole) {
  // Part 1 holds units 0 and 2, part 2 units 1 and 3. Within part 1 both points are on its
  // front (the faster is less accurate); unit 1 of part 2 is faster and more accurate than both.
  const Merged m = merge_parts({sweep_part(2, {{0.5, 0.01}, {9.0, 0.5}}, {1, 3}),
                                sweep_part(1, {{1.0, 0.1}, {2.0, 0.05}}, {0, 2})});
  EXPECT_EQ(m.command, "sweep");
  EXPECT_FALSE(m.json.contains("shard"));
  const ordered_json& points = m.json["scenes"][0]["points"];
  ASSERT_EQ(points.size(), 4u);
  const double order[] = {1.0, 0.5, 2.0, 9.0};  // units 0, 1, 2, 3
  for (std::size_t k = 0; k < 4; ++k)
    EXPECT_EQ(points[k]["ms_per_step"].get<double>(), order[k]) << k;
  EXPECT_FALSE(points[0]["pareto"].get<bool>());
  EXPECT_TRUE(points[1]["pareto"].get<bool>());
  EXPECT_FALSE(points[2]["pareto"].get<bool>());
  EXPECT_FALSE(points[3]["pareto"].get<bool>());
}

TEST(Merge, RefusesPartsThatAreNotOneWholeNamingTheFiles) {
  auto refused = [](const std::vector<ShardPart>& parts) {
    try {
      merge_parts(parts);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("merged");
  };
  const ShardPart a = sweep_part(1, {{1, 1}, {1, 1}}, {0, 2});
  const ShardPart b = sweep_part(2, {{1, 1}, {1, 1}}, {1, 3});
  EXPECT_NE(refused({a}).find("2/2 missing"), std::string::npos);
  EXPECT_NE(refused({a, a, b}).find("part 1/2 again"), std::string::npos);
  EXPECT_NE(refused({a, sweep_part(2, {{1, 1}, {1, 1}}, {1, 3}, "g2")}).find("another sweep"),
            std::string::npos);
  EXPECT_NE(refused({a, sweep_part(2, {{1, 1}, {1, 1}}, {1, 3}, "g1", "1.1")})
                .find("part2.json: written by chainbench 1.1"),
            std::string::npos);
  EXPECT_NE(refused({a, sweep_part(2, {{1, 1}}, {1, 3})}).find("holds 1 points"),
            std::string::npos);
  EXPECT_NE(refused({a, sweep_part(2, {{1, 1}, {1, 1}}, {1, 2})}).find("does not belong"),
            std::string::npos);
  ShardPart whole = a;
  whole.json.erase("shard");
  EXPECT_NE(refused({whole, b}).find("part1.json: not a part"), std::string::npos);
  EXPECT_EQ(refused({a, b}), "merged");
}

}  // namespace
}  // namespace chainbench
