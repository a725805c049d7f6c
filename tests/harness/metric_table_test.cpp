// SPDX-License-Identifier: MIT
// The metric table (judge/metric_table.h) is what the outputs are written from: its rows are
// whole, the docs' table is the one it writes, and the run JSON, the run CSV and the run table
// hold every row where the row says, and nothing of a group the run did not measure.
#include "judge/metric_table.h"
#include "campaign/stress.h"
#include "output/report.h"
#include "run/runner.h"
#include "scenes/scene_library.h"

#include <gtest/gtest.h>

#include <fstream>
#include <set>
#include <sstream>
#include <string>

namespace chainbench {
namespace {

TEST(MetricTable, EveryRowIsWholeAndNamedOnce) {
  std::set<std::string> names, json_keys;
  for (const MetricDef& def : metric_table()) {
    EXPECT_TRUE(names.insert(def.name).second) << def.name << " twice";
    EXPECT_EQ(find_metric(def.name), &def);
    EXPECT_NE(*def.help, '\0') << def.name;
    EXPECT_NE(*def.aggregate, '\0') << def.name;
    EXPECT_NE(*def.reading, '\0') << def.name;
    EXPECT_NE(def.value, nullptr) << def.name;
    EXPECT_EQ(def.details != nullptr, *def.details_keys != '\0') << def.name;
    EXPECT_EQ(def.details != nullptr, *def.details_help != '\0') << def.name;
    if (*def.json_key) {
      EXPECT_TRUE(json_keys.insert(std::string(def.json_block) + "." + def.json_key).second);
    } else {
      EXPECT_EQ(*def.json_block, '\0') << def.name << ": a block without a key";
    }
    // A row is written somewhere, under a name in each place it is written.
    EXPECT_TRUE(*def.json_key || def.outputs != 0) << def.name << " is written nowhere";
    EXPECT_FALSE((def.outputs & kRunCsv) && (def.outputs & kRunCsvLate)) << def.name;
    if (def.outputs & (kRunTable | kSweep)) {
      EXPECT_NE(*def.column, '\0') << def.name;
    }
    if (def.outputs & kSweep) {
      EXPECT_NE(*def.sweep_key, '\0') << def.name;
    }
    EXPECT_EQ(def.kind == MetricKind::kNumber, *def.unit != '\0') << def.name;
  }
  EXPECT_EQ(find_metric("no such metric"), nullptr);
}

TEST(MetricTable, TheDocsHoldTheTableItWrites) {
  std::ifstream in(std::string(CHAINBENCH_DOCS) + "/output-formats.md");
  ASSERT_TRUE(in) << "docs/output-formats.md";
  std::stringstream text;
  text << in.rdbuf();
  const std::string docs = text.str();
  const std::size_t begin = docs.find("<!-- metrics:begin");
  const std::size_t end = docs.find("<!-- metrics:end -->");
  ASSERT_NE(begin, std::string::npos);
  ASSERT_NE(end, std::string::npos);
  const std::size_t first = docs.find('\n', begin) + 1;
  EXPECT_EQ(docs.substr(first, end - first), metric_docs_table())
      << "docs/output-formats.md §2.5 differs from the metric table: put the output of "
         "`build/bin/chainbench list --metrics` between the markers";
}

RunReport report_of(const Scene& scene, MetricSelection selection) {
  RunOptions options;
  options.metrics = selection;
  RunReport report;
  report.scene = &scene;
  report.runs.push_back(run_engine(scene, parse_engine_spec("chain"), options));
  return report;
}

// A stack knocked by a pusher: every group has figures to show.
TEST(MetricTable, EachOutputHoldsTheRowsTheTablePutsThere) {
  const Scene scene = make_scene("push_stack", {"steps=20"});
  for (const bool all : {true, false}) {
    const RunReport report = report_of(scene, all ? MetricSelection{} : MetricSelection::none());
    const nlohmann::ordered_json metrics = run_json(report)["runs"][0]["metrics"];
    std::ostringstream csv;
    write_run_csv(csv, report);
    const std::string header = csv.str().substr(0, csv.str().find('\n'));
    std::ostringstream table;
    print_run_table(table, report);
    const std::string table_header = table.str().substr(table.str().find("engine"));
    std::size_t csv_at = 0;
    for (const MetricDef& def : metric_table()) {
      SCOPED_TRACE(def.name);
      if (*def.json_key) {
        const bool in_json = *def.json_block ? metrics.contains(def.json_block) &&
                                                   metrics[def.json_block].contains(def.json_key)
                                             : metrics.contains(def.json_key);
        EXPECT_EQ(in_json, all);
      }
      if (def.outputs & (kRunCsv | kRunCsvLate)) {
        // In the header, after the rows before it.
        const std::size_t at = header.find("," + std::string(def.name) + ",");
        ASSERT_NE(at, std::string::npos) << header;
        EXPECT_GT(at, csv_at);
        csv_at = at;
      }
      if (def.outputs & kRunTable) {
        EXPECT_NE(table_header.find(def.column), std::string::npos) << table_header;
      }
    }
  }
}

// A stress case's JSON and table row hold the rows the table gives them, flags as flags.
TEST(MetricTable, StressShowsTheRowsTheTablePutsThere) {
  StressVerdict v;
  v.finished = true;
  v.case_label = "case";
  v.engine = parse_engine_spec("chain");
  for (const MetricDef& def : metric_table())
    v.metrics.push_back(def.kind == MetricKind::kFlag ? 1.0 : 0.25);
  const nlohmann::ordered_json c = stress_json({v}, true)["cases"][0];
  std::ostringstream table;
  print_stress_table(table, {v});
  for (const MetricDef& def : metric_table()) {
    SCOPED_TRACE(def.name);
    EXPECT_EQ(c.contains(def.json_key), (def.outputs & kStressJson) != 0);
    if (def.outputs & kStressJson) {
      EXPECT_EQ(c[def.json_key], def.kind == MetricKind::kFlag ? nlohmann::ordered_json(true)
                                                               : nlohmann::ordered_json(0.25));
    }
    if (def.outputs & kStressTable) {
      EXPECT_NE(table.str().find(def.column), std::string::npos) << table.str();
    }
  }
}

}  // namespace
}  // namespace chainbench
