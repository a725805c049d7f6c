// SPDX-License-Identifier: MIT
// Runs one engine on one scene: builds it (timed as setup), steps it (each step timed on the
// steady clock, the first excluded), records the metrics that were asked for, checks the scene's
// expectations (always: they are the truth a run is judged by) and judges the run. Metrics,
// expectations and traces are computed between steps, outside the timer.
#pragma once

#include "engines/engine_spec.h"
#include "judge/engine_run.h"
#include "judge/metrics.h"
#include "model/scene.h"
#include "run/step_observer.h"

#include <atomic>
#include <cmath>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace chainbench {

struct RunOptions {
  MetricSelection metrics;
  // Shown every step of the run (step_observer.h): traces, replay pages.
  std::vector<StepObserver*> observers;
  // Called now and then with (steps done, steps in all): for progress bars.
  std::function<void(int, int)> progress;
  // When set, the run stops after the current step and is marked interrupted.
  const std::atomic<bool>* stop = nullptr;
  // Engines whose code the harness does not own (EngineDef::isolated: plugins) run in a child
  // process (isolated_run.h), killed after timeout_s seconds; built-in engines run in process.
  bool isolate = false;
  double timeout_s = HUGE_VAL;
  // Ask the engine to time its step's stages (EngineRun::stages).
  bool stages = false;
  // When set, holds the step under way (counted from 1, as verdicts count "at step N") from the
  // moment it starts; untouched before the first.
  std::atomic<int>* step_mark = nullptr;
};

// The figures of a run's step times (ms, any order): median, mean, p95 and p99 by nearest rank,
// max, spread. Empty samples give zeros.
Timing summarize_steps(std::vector<double> samples, double setup_ms);

EngineRun run_engine(const Scene& scene, const EngineSpec& spec, const RunOptions& options);

}  // namespace chainbench
