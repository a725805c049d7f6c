// SPDX-License-Identifier: MIT
// What `chainbench run` reports: a table for people (report.cpp), JSON (chainbench.run/1,
// docs/output-formats.md §2; run_json.cpp) and CSV (§3; run_csv.cpp) for tools.
#pragma once

#include "judge/engine_run.h"
#include "judge/metrics.h"
#include "model/scene.h"

#include <nlohmann/json.hpp>

#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace chainbench {

struct Comparison {
  std::string engine;
  std::string reference;
  PositionError error;
  double speedup = 0.0;  // reference median ms/step over the engine's
};

struct RunReport {
  const Scene* scene = nullptr;
  std::vector<EngineRun> runs;
  std::optional<EngineRun> reference;        // the reference run, when it was not one of `runs`
  std::optional<EngineSpec> reference_spec;  // none: no reference
  std::vector<Comparison> comparison;        // each run against the reference, in run order
  bool interrupted = false;  // Ctrl-C: `runs` holds the engines that finished before it
};

// An engine limit (registry.h) the run's scene exceeds: the engine's label, the limit as listed
// and as a speed here (m/s), and the fastest the scene asks (stated, or measured in some run).
struct LimitNote {
  std::string engine;
  std::string what;
  double value = 0.0;
  std::string unit;
  double speed_limit = 0.0;
  double asked = 0.0;
  std::string source;  // "bullet's initial velocity", "bullet in chain's run"
};
std::vector<LimitNote> exceeded_limits(const RunReport& report);

// Calls visit(def) for every counter every run of `report` declares: its runs in order, then the
// reference run; a counter two engines declare comes twice.
template <class Visit>
void for_each_counter_def(const RunReport& report, Visit&& visit) {
  for (const EngineRun& run : report.runs) {
    for (const CounterDef& c : run.counter_defs())
      visit(c);
  }
  if (report.reference) {
    for (const CounterDef& c : report.reference->counter_defs())
      visit(c);
  }
}

// Fills report.comparison from report.runs and the reference.
void compare(RunReport& report);
// The reference's run (one of report.runs, or report.reference), or null without one.
const EngineRun* reference_of(const RunReport& report);
// The comparison of `run` with the reference, or null (the reference itself, or no reference).
const Comparison* comparison_of(const RunReport& report, const EngineRun& run);

void print_run_table(std::ostream& out, const RunReport& report);
nlohmann::ordered_json run_json(const RunReport& report);
void write_run_csv(std::ostream& out, const RunReport& report);

// A number for JSON: null when not finite (JSON has no NaN or infinity).
nlohmann::ordered_json json_number(double v);
// An expect entry as the scene states it: kind, body ("*" for every dynamic body), its figures
// and its window (from_step, to_step) when it has one.
nlohmann::ordered_json expectation_json(const Scene& scene, const Expectation& e);

}  // namespace chainbench
