// The metrics of DESIGN.md, computed by the harness from positions and velocities, the same way
// for every engine. Only what is selected is computed: with nothing selected a run steps bare.
#pragma once

#include "engine.h"
#include "overlap_scan.h"
#include "scene.h"

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace chainbench {

struct MetricSelection {
  bool displacement = true;  // energy-free displacement
  bool penetration = true;   // max penetration
  bool stability = true;     // finite, in bounds, peak speed against its bound

  static MetricSelection none() { return {false, false, false}; }
  bool any() const { return displacement || penetration || stability; }
};

// Parses "all", "none" or a comma list of displacement, penetration, stability.
MetricSelection parse_metric_selection(const std::string& text);

struct Metrics {
  // Energy-free displacement: d_i^n = |x_i^{n+1} - x_i^n - h v_i^{n+1}| over dynamic bodies.
  std::optional<double> efd_total, efd_per_body_step, efd_max_step;
  std::optional<double> max_penetration;
  std::optional<double> peak_speed;
  std::optional<double> speed_bound;  // what gravity, drives and initial velocities can give
  std::optional<bool> finite, in_bounds, blow_up;
};

class MetricsRecorder {
 public:
  MetricsRecorder(const Scene& scene, MetricSelection selection);
  // Call after every step with the state before and after it. Fills step_displacement() and
  // step_penetration() (per body, this step) when `per_body` is true.
  void observe(const BodyState& before, const BodyState& after, bool per_body);
  Metrics result() const;
  std::span<const double> step_displacement() const { return step_efd_; }
  std::span<const double> step_penetration() const { return step_pen_; }

 private:
  MetricSelection sel_;
  double dt_;
  std::vector<std::size_t> dynamic_;
  Vec2d center_;
  double bound_radius_;
  double speed_bound_;
  std::optional<OverlapScan> scan_;
  std::vector<double> step_efd_, step_pen_;
  double efd_total_ = 0.0, efd_max_ = 0.0, max_pen_ = 0.0, peak_speed_ = 0.0;
  std::uint64_t body_steps_ = 0;
  bool finite_ = true, in_bounds_ = true;
};

// FNV-1a, 64 bit, over the bit patterns of every final position (x then y, scene order).
std::uint64_t position_hash(std::span<const Vec2d> positions);
std::string hex(std::uint64_t v);

struct PositionError {
  double max = 0.0;
  double rms = 0.0;
};
// |x_i - x_i^ref| over the dynamic bodies.
PositionError position_error(const Scene& scene, std::span<const Vec2d> run,
                             std::span<const Vec2d> reference);

}  // namespace chainbench
