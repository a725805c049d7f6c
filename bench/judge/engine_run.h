// SPDX-License-Identifier: MIT
// What one engine's run of one scene comes to: its step times, final state, metrics, counters,
// expectations and verdict. Plain data that the run loop (run/runner.h) fills and every writer,
// campaign and judge reads.
#pragma once

#include "engines/engine_spec.h"
#include "engines/registry.h"
#include "judge/expectations.h"
#include "judge/metrics.h"
#include "judge/verdict.h"
#include "model/scene.h"

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace chainbench {

struct Timing {
  double median_ms = 0.0;
  double mean_ms = 0.0;
  double p95_ms = 0.0;
  double p99_ms = 0.0;  // nearest rank, as p95
  double max_ms = 0.0;  // the slowest step timed: the frame a game must budget for
  // Half the interquartile range of the step times: how far apart two medians must be before one
  // engine can be called faster than another.
  double spread_ms = 0.0;
  double setup_ms = 0.0;
  int samples = 0;
  friend bool operator==(const Timing&, const Timing&) = default;
};

// One stage of an engine's step (Engine::stages) and its mean wall time over the timed steps.
struct StageMean {
  std::string name;
  double ms = 0.0;
  friend bool operator==(const StageMean&, const StageMean&) = default;
};

struct EngineRun {
  EngineSpec spec;
  std::string engine;  // spec.str(), the canonical spec
  // Every body's centre and angle in the last state, final_state (the steps taken); a body out of
  // the world then (SceneBody::alive) holds zeros, which no output shows (present_at_end).
  std::vector<Vec2d> final_positions;
  std::vector<double> final_angles;
  int final_state = 0;
  Timing timing;
  Metrics metrics;
  bool metrics_computed = false;
  std::uint64_t hash = 0;
  // The engine's counters (registry.h) aggregated over the run, in the order it declares them.
  std::vector<double> counters;
  std::uint64_t degraded_steps = 0;  // steps the engine cut short (the chain's budget)
  std::optional<ExpectResult> expect;
  std::optional<Verdict> verdict;  // judged when stability and penetration were measured
  bool interrupted = false;        // stopped before its last step
  // Set when the run's child process (isolated_run.h) crashed, hung or exited without its result,
  // or its plugin failed a step: why ("died of signal 11 (SIGSEGV) at step 2", or the plugin's
  // error); the run then holds no figures, and its verdict is crash, hang or error.
  std::optional<std::string> failure;

  // Finite, no body escaped, no blow-up, no body through another, and no step cut short; empty
  // when not measured.
  std::optional<bool> stable() const;
  // Whether body i of `scene` (the run's) is in the world in the run's last state.
  bool present_at_end(const Scene& scene, std::size_t i) const {
    return scene.bodies[i].alive(final_state);
  }
  // The run's value of the counter `name`, or empty when its engine has no such counter.
  std::optional<double> counter(std::string_view name) const;
  const std::vector<CounterDef>& counter_defs() const { return defs; }

  std::vector<CounterDef> defs;  // what the engine counts, in the order of `counters`
  // The engine's own stage times (RunOptions::stages), over the same steps as `timing`; empty
  // when not asked for or when the engine measures none.
  std::vector<StageMean> stages;

  // Every field equal: a run carried from a child process (isolated_run.h) is the run itself.
  friend bool operator==(const EngineRun&, const EngineRun&) = default;
};

}  // namespace chainbench
