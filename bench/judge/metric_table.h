// SPDX-License-Identifier: MIT
// The metrics of a run (judge/metrics.h) as a table: one row per figure, with its unit, what it
// says, how the steps make it and how it is read, and the name it goes by in each output that
// shows it. The run JSON's `metrics` block, the run CSV's metric columns, the metric columns of the
// run and sweep tables, the sweep JSON and CSV, and the table in docs/output-formats.md §2.5 are
// all written from it (tests/harness/metric_table_test.cpp holds the docs to it). A new metric is
// a row here and its computation in MetricsRecorder: the outputs follow.
#pragma once

#include "judge/metrics.h"
#include "model/scene.h"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <optional>
#include <span>
#include <string>

namespace chainbench {

// The --metrics group a figure is measured with: present in an output only when measured.
enum class MetricGroup { kDisplacement, kPenetration, kStability };
const char* to_string(MetricGroup group);
// Whether `m` holds the figures of `group` (a run measures only the groups it was asked for).
bool measured(const Metrics& m, MetricGroup group);

// What kind of value a figure is, and so how each output writes it: a number (JSON number, CSV
// to 9 digits, tables to 3), a flag (JSON true/false, CSV 1/0, tables yes/NO) or a count.
enum class MetricKind { kNumber, kFlag, kCount };

// Where a figure is shown, beside the run JSON's `metrics` block that holds every one.
enum MetricOutput : std::uint32_t {
  kRunCsv = 1u << 0,       // a column of the run CSV, among the first metric columns
  kRunCsvLate = 1u << 1,   // a column of the run CSV after the run's own figures (a later column)
  kRunTable = 1u << 2,     // a column of `chainbench run`'s table
  kSweep = 1u << 3,        // a column of the sweep's table and CSV, a key of its JSON points
  kStressJson = 1u << 4,   // a key of each stress case (flags with the run's flags, figures after
                           // its counters)
  kStressTable = 1u << 5,  // a column of the stress table
};

struct MetricDef {
  const char* name;  // the figure's name: its run CSV and sweep CSV column
  MetricGroup group;
  MetricKind kind;
  const char* unit;       // "m", "m/s", or "" for flags and counts
  const char* aggregate;  // how the run's steps make the figure
  const char* reading;    // how it is read: which value is right
  const char* help;       // what it measures, for docs and tables
  // Run JSON: the object inside `metrics` that holds it ("" for `metrics` itself) and its key.
  const char* json_block;
  const char* json_key;
  const char* column;                              // the text tables' title, when a table shows it
  const char* sweep_key;                           // the sweep JSON's key, when the sweep shows it
  std::uint32_t outputs;                           // MetricOutput bits
  std::optional<double> (*value)(const Metrics&);  // flags as 1 or 0; empty when not measured
  // What the run JSON writes beside the value, into the `metrics` block (worst_overlap beside
  // max_penetration, say), and those keys and their meaning for the docs; none when null.
  void (*details)(nlohmann::ordered_json& metrics, const Metrics&, const Scene&) = nullptr;
  const char* details_keys = "";
  const char* details_help = "";
};

// Every metric, in the order the run JSON writes them.
std::span<const MetricDef> metric_table();
// Most rows the table may hold (a stress case's child sends them back in a fixed-size record).
inline constexpr std::size_t kMaxMetrics = 32;
// The row named `name` (MetricDef::name); nullptr when there is none.
const MetricDef* find_metric(const std::string& name);

// A figure as the text tables show it: 3 significant digits, yes/NO, or "-" when empty.
std::string metric_cell(const MetricDef& def, const std::optional<double>& value);
// A figure as the CSVs write it: 9 significant digits, 1/0, or nothing when empty.
std::string metric_csv(const MetricDef& def, const std::optional<double>& value);

// docs/output-formats.md §2.5's table of the metrics, as Markdown: what the docs must hold.
std::string metric_docs_table();

}  // namespace chainbench
