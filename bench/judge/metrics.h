// SPDX-License-Identifier: MIT
// The metrics of a run, computed by the harness from positions and velocities, the same way for
// every engine. Only what is selected is computed: with nothing selected a run steps bare.
#pragma once

#include "engines/engine.h"
#include "index/pair_cache.h"
#include "index/pair_scan.h"
#include "index/presence.h"
#include "judge/motion_bounds.h"
#include "judge/tunnelling.h"
#include "model/scene.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace chainbench {

struct MetricSelection {
  bool displacement = true;  // energy-free displacement
  bool penetration = true;   // max penetration, and penetration against the scene's tolerance
  bool stability = true;     // finite, escapes, tunnelling, peak speed against its bound

  static MetricSelection none() { return {false, false, false}; }
  bool any() const { return displacement || penetration || stability; }
};

// Parses "all", "none" or a comma list of displacement, penetration, stability.
MetricSelection parse_metric_selection(const std::string& text);

// An overlap between two bodies in some state.
struct PairOverlap {
  double depth = 0.0;  // m, along the axis of least penetration
  std::size_t a = 0, b = 0;
  int step = 0;            // the state (steps taken)
  double tolerance = 0.0;  // what the pair may overlap before the run is penetrating, m
  friend bool operator==(const PairOverlap&, const PairOverlap&) = default;
};

struct Metrics {
  // Energy-free displacement: d_i^n = |x_i^{n+1} - x_i^n - h v_i^{n+1}| over dynamic bodies.
  std::optional<double> efd_total, efd_per_body_step, efd_max_step;
  std::optional<double> max_penetration;
  // The overlap furthest beyond its tolerance (deepest relative to it) over the run.
  std::optional<PairOverlap> worst_overlap;
  // Fastest displacement of any dynamic body in a step, divided by dt (m/s): measured from
  // positions, so that no velocity rule can hide a body thrown across the scene.
  std::optional<double> peak_speed;
  std::size_t peak_speed_body = 0;
  int peak_speed_step = 0;
  // The largest per-body speed bound (motion_bounds.h); none when the scene bounds no speed, and
  // then why.
  std::optional<double> speed_bound;
  std::string speed_unbounded;
  // Blow-up: over some stretch of steps a body travelled further than its speed bound allows in
  // that time, by more than its allowance (motion_bounds.h), not counting pushes out of overlaps
  // it was in and single-precision rounding. The body, the step it crossed that line and its
  // speed then.
  std::optional<bool> finite, blow_up, tunnelled;
  std::size_t blow_up_body = 0;
  int blow_up_step = 0;
  double blow_up_speed = 0.0;
  double blow_up_bound = 0.0;  // that body's speed bound
  // Escapes: bodies that ended farther from their start than anything in the scene could send
  // them (judged per body: the body's own speed bound over the run, plus initial overlaps).
  std::optional<bool> in_bounds;
  std::vector<std::size_t> escaped;
  std::optional<TunnelEvent> tunnel;  // the first body seen passing through another
  std::uint64_t tunnel_count = 0;
  // Every field equal (a NaN figure equals nothing): what a run carried from a child process
  // (isolated_run.h) must be.
  friend bool operator==(const Metrics&, const Metrics&) = default;
};

class MetricsRecorder {
 public:
  MetricsRecorder(const Scene& scene, MetricSelection selection);
  // Call after every step with the state before and after it and the step's number (1 for the
  // first step); `before` is the `after` of the previous call (or the initial state). `changed`,
  // when given, lists (ascending) every body whose state differs between the two. Fills
  // step_displacement() and step_penetration() (per body, this step) when `per_body` is true, and
  // last_deepest() when `depth` is true or penetration is selected.
  //
  // The cost follows what moved: a step that moved nothing costs one pass comparing the two
  // states, and one that moved some bodies a pass more over the pairs listed for them by a
  // PairCache (metrics_observe.cpp). The figures are those of a full scan.
  //
  // Where bodies come and go (SceneBody::from_step), a body counts only while it is in the world
  // (presence.h): in the overlaps of the states it is in, and in displacement, speed, blow-up and
  // tunnelling over the steps it takes part in (both states of the step). What the states hold
  // for a body outside its life is never read for a figure, so a body entering is no move, and
  // one that left is judged for escape where it was last.
  void observe(const BodyState& before, const BodyState& after, int step, bool per_body,
               bool depth = false, const std::vector<std::uint32_t>* changed = nullptr);
  // Every step from now on scans every body: the check the shortcuts are tested against.
  void scan_every_body() {
    every_body_ = true;
    full_scan_.emplace(scene_);
  }
  // The metrics of the run that ended in `last`.
  Metrics result(const BodyState& last) const;
  std::span<const double> step_displacement() const { return step_efd_; }
  std::span<const double> step_penetration() const { return step_pen_; }
  // The deepest overlap of the state after the last observed step (for expectations).
  const PairOverlap& last_deepest() const { return deepest_; }
  // Which bodies are in the world in the state of the last observed step.
  const Presence& presence() const { return presence_; }

  // The deepest overlap in `state`, found with a scan of its own (the initial state, say).
  static PairOverlap deepest_overlap(const Scene& scene, const BodyState& state, int step);

 private:
  // How deep pair (i, j) overlapped in the initial state (0 if apart).
  double initial_depth(std::size_t i, std::size_t j) const;
  // A pair overlapping after a step, as the step's figures count it.
  struct Overlap {
    std::uint32_t a, b;  // a < b
    double depth, tolerance;
  };
  // Both bodies entered the world in state k: they stand as the file placed them, no step having
  // moved them (the next state judges what the engine made of their overlap).
  bool placed(std::size_t a, std::size_t b, int k) const {
    return lives_ && k > 0 && scene_.bodies[a].from_step == k && scene_.bodies[b].from_step == k;
  }
  // Lists in moved_ the bodies the step from `before` to `after` moved (or left with a velocity);
  // false, with the list unfinished, when more than half did (a full pass is cheaper then).
  bool find_moved(const BodyState& before, const BodyState& after);
  // The same from `changed` and the bodies the last step left with a velocity (still_).
  bool find_moved(const BodyState& before, const BodyState& after,
                  const std::vector<std::uint32_t>& changed);
  // Whether body i moved in the step, or was left with a velocity or a position that is not finite
  // (whose displacement a full pass finds to be NaN every step).
  // A body out of the world in both states never moved, whatever its entries hold.
  bool moved(std::size_t i, const BodyState& before, const BodyState& after) const {
    return (after.position[i].x != before.position[i].x ||
            after.position[i].y != before.position[i].y ||
            (scan().rotated() && after.angle[i] != before.angle[i]) || keeps_moving(i, after)) &&
           (!lives_ || presence_.in(i) || presence_.was(i));
  }
  // Merges into moved_ the bodies that entered or left in the step (their pairs change); false
  // when more than half of the bodies are then on it.
  bool add_changes(std::size_t bodies);
  // Whether body i took part in the step observed: in the world before and after it.
  bool stepped(std::size_t i) const { return !lives_ || presence_.stepped(i); }
  // Whether body i is in the world in the state observed.
  bool present(std::size_t i) const { return !lives_ || presence_.in(i); }
  // Dynamic bodies that took part in the step observed.
  std::size_t dynamic_stepped() const {
    return lives_ ? presence_.dynamic_stepped() : dynamic_.size();
  }
  // Escapes of the bodies that left in the step from `before`, judged where they were last.
  void judge_leavers(const BodyState& before);
  // Whether body i at p is farther from its start than the scene can send it.
  bool escaped(std::size_t i, Vec2d p) const;
  static bool keeps_moving(std::size_t i, const BodyState& s) {
    return s.velocity[i].x != 0.0 || s.velocity[i].y != 0.0 || !std::isfinite(s.position[i].x) ||
           !std::isfinite(s.position[i].y);
  }
  void observe_all(const BodyState& before, const BodyState& after, int step, bool displacement,
                   bool overlaps);
  void observe_some(const BodyState& before, const BodyState& after, int step, bool displacement,
                    bool overlaps);
  void observe_still(const BodyState& after, int step, bool displacement, bool overlaps);
  // Judges pair (i, j) over the step: tunnelling, and into fresh_ when it overlaps.
  void visit(const BodyState& before, const BodyState& after, std::size_t i, std::size_t j,
             int step);
  // The step's deepest overlap and each body's deepest, from fresh_.
  void settle(int step);
  void clear_displacements();
  // Body i's energy-free displacement over the step, added to the run's figures and step_efd_.
  double add_displacement(const BodyState& before, const BodyState& after, std::size_t i);
  // Body i's finiteness, speed and blow-up bucket over the step from `before` to `after`.
  void update_slack(const BodyState& before, const BodyState& after, std::size_t i, int step);

  MetricSelection sel_;
  const Scene& scene_;
  Presence presence_;
  bool lives_ = false;                 // some body comes or goes (presence_.any())
  bool filters_ = false;               // some pairs do not collide (Scene::filters())
  std::vector<std::size_t> left_out_;  // bodies that escaped before they left, ascending
  double dt_;
  MotionBounds bounds_;
  std::vector<std::size_t> dynamic_;
  PairCache cache_;                    // the pairs of every step but those of scan_every_body()
  std::optional<PairScan> full_scan_;  // scan_every_body()'s
  // The boxes' sizes and kinds, and the overlap of two of them.
  const PairScan& scan() const { return cache_.scan(); }
  TunnelWatch tunnels_;
  std::vector<double> step_efd_, step_pen_;
  std::vector<double> slack_;  // per body: what is left of its allowance, m
  // Dynamic bodies whose slack is below their allowance, in scene order: besides the bodies that
  // moved, the only ones whose bucket a step changes.
  std::vector<std::size_t> recovering_, merged_;
  std::vector<std::uint32_t> moved_;  // ascending
  // The bodies that keep_moving() after the last step observed, ascending: with the bodies whose
  // state changed, the only ones a step can find moved.
  std::vector<std::uint32_t> still_, candidates_;
  std::vector<std::uint8_t> active_;  // per body: in moved_ (set while a step is observed)
  // The pairs overlapping after the last step measured, and those of this step.
  std::vector<Overlap> overlaps_, fresh_;
  // step_efd_'s non-zero entries: every dynamic body's (dense), or these.
  bool efd_dense_ = false;
  bool every_body_ = false;
  std::vector<std::size_t> efd_written_;
  std::vector<double> depth_;  // per body: its deepest overlap in the last state observed, m
  double efd_total_ = 0.0, efd_max_ = 0.0, max_pen_ = 0.0;
  double peak_speed_ = 0.0;
  std::size_t peak_body_ = 0;
  int peak_step_ = 0;
  bool blow_up_ = false;
  std::size_t blow_up_body_ = 0;
  int blow_up_step_ = 0;
  double blow_up_speed_ = 0.0, blow_up_bound_ = 0.0;
  PairOverlap deepest_, worst_;
  double worst_ratio_ = 0.0;
  std::uint64_t body_steps_ = 0;
  bool finite_ = true;
  // The last step observed, and the last whose overlaps were measured (-2: none).
  int last_step_ = -2, overlaps_step_ = -2;
};

// Whether a difference of `value` between quantities of magnitude `magnitude` is rounding: at or
// below two units in the last place of that magnitude. Such figures are reported as 0.
// Inline: the metrics ask it of every body and pair they judge.
inline bool below_resolution(double value, double magnitude) {
  const double m = std::abs(magnitude);
  if (!std::isfinite(value) || !std::isfinite(m)) return false;
  // One unit in the last place of m (for m = 0, of the smallest normal double): the next double
  // up from a finite m >= 0 is the one whose bits are one more, as std::nextafter finds it.
  const double ulp = m > 0.0 ? std::bit_cast<double>(std::bit_cast<std::uint64_t>(m) + 1u) - m
                             : std::numeric_limits<double>::min();
  return std::abs(value) <= 2.0 * ulp;
}
// The larger absolute coordinate of p: the magnitude a position's rounding is judged against.
inline double magnitude(Vec2d p) {
  return std::max(std::abs(p.x), std::abs(p.y));
}

// FNV-1a, 64 bit, over the bit patterns of every final position (x then y, scene order).
std::uint64_t position_hash(std::span<const Vec2d> positions);
std::string hex(std::uint64_t v);

struct PositionError {
  double max = 0.0;
  double rms = 0.0;
};
// |x_i - x_i^ref| over the dynamic bodies (differences below resolution count as 0); with
// `state` >= 0, over those in the world in that state (SceneBody::alive) only.
PositionError position_error(const Scene& scene, std::span<const Vec2d> run,
                             std::span<const Vec2d> reference, int state = -1);

// The scene's initial state: centres and initial velocities, angles 0.
BodyState initial_state(const Scene& scene);

}  // namespace chainbench
