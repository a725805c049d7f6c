// SPDX-License-Identifier: MIT
// The run CSV reads as columns: every counter of every engine in the run is a column of its own
// (counter_NAME), beside the packed `counters` field, each row holding its own engine's value and
// nothing where its engine has no such counter.
#include "cli_run.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

namespace {

// One CSV line split into fields (double quotes around a field that holds commas).
std::vector<std::string> fields(const std::string& line) {
  std::vector<std::string> out(1);
  bool quoted = false;
  for (char c : line) {
    if (c == '"') {
      quoted = !quoted;
    } else if (c == ',' && !quoted) {
      out.emplace_back();
    } else {
      out.back() += c;
    }
  }
  return out;
}

TEST(CliCsv, EveryCounterIsAColumnOfItsOwn) {
  const std::string path =
      (std::filesystem::temp_directory_path() / "chainbench_cli_csv_counters.csv").string();
  const cli::Result r = cli::chainbench(
      "run --scene pyramid --set base=4 --engines chain,box2d "
      "--reference none --metrics none --csv " +
      path);
  ASSERT_EQ(r.status, 0) << r.out;
  std::ifstream csv(path);
  std::string line;
  std::getline(csv, line);
  const std::vector<std::string> header = fields(line);
  std::vector<std::map<std::string, std::string>> rows;
  while (std::getline(csv, line)) {
    const std::vector<std::string> cells = fields(line);
    ASSERT_EQ(cells.size(), header.size()) << line;
    std::map<std::string, std::string> row;
    for (std::size_t i = 0; i < cells.size(); ++i)
      row[header[i]] = cells[i];
    rows.push_back(row);
  }
  std::remove(path.c_str());
  ASSERT_EQ(rows.size(), 2u);
  // Each packed counter is also in its column, with the same text.
  for (const auto& row : rows) {
    std::string packed = row.at("counters");
    for (std::size_t at = 0; at < packed.size();) {
      const std::size_t end = std::min(packed.find(';', at), packed.size());
      const std::string pair = packed.substr(at, end - at);
      const std::size_t eq = pair.find('=');
      ASSERT_NE(eq, std::string::npos) << packed;
      ASSERT_TRUE(row.count("counter_" + pair.substr(0, eq))) << pair;
      EXPECT_EQ(row.at("counter_" + pair.substr(0, eq)), pair.substr(eq + 1)) << pair;
      at = end + 1;
    }
  }
  // The chain's counters first (its run comes first), Box2D's contacts among them once; Box2D
  // has no skipped steps, so its cell is empty.
  EXPECT_TRUE(rows[0].count("counter_skipped_steps"));
  EXPECT_EQ(rows[1].at("counter_skipped_steps"), "");
  EXPECT_NE(rows[1].at("counter_contacts"), "");
}

}  // namespace
