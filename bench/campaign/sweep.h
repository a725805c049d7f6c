// SPDX-License-Identifier: MIT
// Error against run time: one scene run over a grid of engine settings, each point measured
// against a reference more accurate than any point (or against the scene's expectations), and
// the points on the Pareto front of (ms/step, error) marked.
#pragma once

#include "engines/engine_spec.h"
#include "judge/metrics.h"
#include "model/scene.h"
#include "run/runner.h"

#include <nlohmann/json.hpp>

#include <atomic>
#include <cmath>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

namespace chainbench {

struct SweepPoint {
  EngineRun run;
  PositionError error;  // against the reference run, or the scene's expectations
  bool pareto = false;
};

// One value of the scene parameter `sweep --vary` steps through ("dt", "1/30", 0.0333...).
struct SweepVariant {
  std::string key;
  std::string text;  // as the user wrote it
  double value = 0.0;
};

struct SweepResult {
  std::string scene;
  std::optional<SweepVariant>
      variant;  // set by `sweep --vary`: the value this scene was built with
  int bodies = 0;
  int steps = 0;
  std::string reference;  // the reference engine spec, or "expect"
  std::string reference_label;
  std::optional<EngineRun> reference_run;
  std::vector<SweepPoint> points;
  bool interrupted = false;
};

struct SweepOptions {
  const std::atomic<bool>* stop = nullptr;  // set (by Ctrl-C) to stop after the current point
  // Per grid point, whether to run it (a shard runs a part, shard.h); empty: every point. With
  // none to run, the reference does not run either.
  std::vector<bool> include;
  std::function<void(const std::string&, int, int)> progress;  // (label, done, total) points
  // Seconds a point of an engine run in a child process (plugins, isolated_run.h) may take
  // before it counts as a hang.
  double timeout_s = HUGE_VAL;
};

// Runs every spec on the scene (those included); the reference first (unless the scene has
// expectations).
SweepResult sweep(const Scene& scene, const std::vector<EngineSpec>& grid,
                  const EngineSpec& reference, const SweepOptions& options);

// How far a point's median ms/step may be from its true value: half the interquartile range of its
// step times, and at least 5% of the median.
double timing_noise(const Timing& t);
// Marks the points no other point beats on both ms/step and RMS error; a point is faster than
// another only by more than their timing noise together. Points whose verdict is unstable,
// escaped, tunnelled or worse are never on the front, and beat none.
void mark_pareto(std::vector<SweepPoint>& points);

// "stack", or "stack (dt=1/30)" for a scene built with one value of `sweep --vary`.
std::string sweep_scene_label(const SweepResult& result);
void print_sweep_table(std::ostream& out, const SweepResult& result);
nlohmann::ordered_json sweep_json(const std::vector<SweepResult>& results);
void write_sweep_csv(std::ostream& out, const std::vector<SweepResult>& results);

}  // namespace chainbench
