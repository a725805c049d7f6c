// Error against run time: one scene run over a grid of engine settings, each point measured
// against a reference more accurate than any point (or against the scene's expectations), and
// the points on the Pareto front of (ms/step, error) marked.
#pragma once

#include "engine_spec.h"
#include "metrics.h"
#include "runner.h"
#include "scene.h"

#include <nlohmann/json.hpp>

#include <atomic>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

namespace chainbench {

// The reference of a sweep when the scene has no expectations: Box2D at 8 sub-steps and 20/10
// iterations, finer than any default point.
inline constexpr const char* kSweepReference = "box2d:vel_iters=20,pos_iters=10,substeps=8";

// "NAME:key=v1,v2;key=v3,v4" -> every combination of the listed values, the other keys at their
// defaults. Throws InputError for unknown engines, keys or values, or more than 10,000 points.
std::vector<EngineSpec> parse_grid(std::string_view text);
// One setting at a time around the defaults: Box2D's velocity and position iterations and
// sub-steps; the chain variants and velocity rules, sweeps and budgets. About 20 points.
std::vector<EngineSpec> default_grid();

struct SweepPoint {
  EngineRun run;
  PositionError error;  // against the reference run, or the scene's expectations
  bool pareto = false;
};

struct SweepResult {
  std::string scene;
  int bodies = 0;
  int steps = 0;
  std::string reference;  // the reference engine spec, or "expect"
  std::optional<EngineRun> reference_run;
  std::vector<SweepPoint> points;
  bool interrupted = false;
};

struct SweepOptions {
  const std::atomic<bool>* stop = nullptr;  // set (by Ctrl-C) to stop after the current point
  std::function<void(const std::string&, int, int)> progress;  // (label, done, total) points
};

// Runs every spec on the scene; the reference first (unless the scene has expectations).
SweepResult sweep(const Scene& scene, const std::vector<EngineSpec>& grid,
                  const std::string& reference, const SweepOptions& options);

// How far a point's median ms/step may be from its true value: half the interquartile range of its
// step times, and at least 5% of the median.
double timing_noise(const Timing& t);
// Marks the points no other point beats on both ms/step and RMS error; a point is faster than
// another only by more than their timing noise together.
void mark_pareto(std::vector<SweepPoint>& points);

void print_sweep_table(std::ostream& out, const SweepResult& result);
nlohmann::ordered_json sweep_json(const std::vector<SweepResult>& results);
void write_sweep_csv(std::ostream& out, const std::vector<SweepResult>& results);

}  // namespace chainbench
