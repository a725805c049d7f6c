// SPDX-License-Identifier: MIT
// The stiff and extreme cases of `chainbench stress`: a matrix of scenes, each run in every
// engine in a child process of its own (a crash or a hang is a verdict, not the end of the
// run), each judged as every run is (verdict.h) against the right answer its scene states.
#pragma once

#include "engines/engine_spec.h"
#include "judge/verdict.h"

#include <nlohmann/json.hpp>

#include <atomic>
#include <cstdint>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

namespace chainbench {

struct StressCase {
  std::string group;  // what the case varies: "mass ratio", "time step", "squeeze" ...
  std::string scene;  // a built-in scene; its recipe states the right answer (expect entries,
                      // penetration tolerance), so the case holds no knowledge of its own
  std::vector<std::string> sets;
  bool quick = false;         // part of --quick
  std::string label() const;  // "push_into_wall n=10000"
};

// The full matrix; cases with quick = true form --quick.
std::vector<StressCase> stress_cases();

struct StressVerdict {
  std::string case_label, group;
  EngineSpec engine;
  bool finished = false;  // false: the child crashed or ran out of time
  bool hang = false;
  bool interrupted = false;    // stopped by Ctrl-C before it finished
  int signal = 0;              // the signal that ended the child, if one did
  int exit_status = 0;         // or its exit status, if it exited without a result
  int step = -1;               // the step under way when it crashed or ran out of time, or -1
  bool out_of_memory = false;  // it ended near its memory cap (child_process.h)
  std::string error;           // the run failed with an exception in the child
  VerdictClass judged = VerdictClass::kOk;  // the child's verdict on a finished run
  std::string detail;                       // what it rests on
  bool near_miss = false;  // every failed check of the child's verdict was a near miss (verdict.h)
  bool expect_pass = true;
  std::uint64_t degraded_steps = 0;
  struct Counter {
    std::string name, column;
    double value;
  };
  std::vector<Counter> counters;  // the engine's counters over the run (engine.h)
  // The run's metrics, one per row of metric_table() in its order (empty: not measured, or
  // not finished); metric(k) and metric_named() read them.
  std::vector<std::optional<double>> metrics;
  std::optional<double> metric(std::size_t k) const {
    return k < metrics.size() ? metrics[k] : std::nullopt;
  }
  // The metric of that name (MetricDef::name), or empty when not measured or not in the table.
  std::optional<double> metric_named(std::string_view name) const;
  double ms_per_step = 0.0, wall_s = 0.0;
  std::string known_failure;  // the reason, when this case and engine are a known failure
  std::string skipped;        // why the engine could not run the case (it was not run)

  VerdictClass verdict() const;  // crash, hang, error, or the child's verdict
  std::string verdict_detail() const;
  bool stable() const;
  // A finished run whose verdict is a near miss.
  bool near() const { return finished && error.empty() && near_miss; }
  // Whether this verdict fails the stress run: the engine is a gate (registry.h) and the verdict
  // is anything but ok or budget on a case not listed as its known failure.
  bool fatal() const;
};

// Runs one case in one engine in a child process, killed after `timeout_s` seconds, or as soon as
// `stop` is set (then the verdict's `interrupted` is set and it says nothing of the engine).
StressVerdict run_stress_case(const StressCase& c, const EngineSpec& engine, double timeout_s,
                              const std::atomic<bool>* stop = nullptr);

void print_stress_table(std::ostream& out, const std::vector<StressVerdict>& verdicts);
// `interrupted`: Ctrl-C stopped the matrix; `verdicts` are the runs that finished before it.
nlohmann::ordered_json stress_json(const std::vector<StressVerdict>& verdicts, bool quick,
                                   bool interrupted = false);

}  // namespace chainbench
