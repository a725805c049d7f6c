// SPDX-License-Identifier: MIT
// What a replay page (replay_page.h) shows of each engine's run, gathered while the runs step:
// an observer (step_observer.h) given to every run of `run --replay` and `replay`. Per engine it
// keeps the positions (position_stream.h, quantised), the chart's series at every step in full
// precision, and the engine's events and counted events by step. The reference must run first:
// the error series measures every later engine against its positions, kept for every step.
#pragma once

#include "engines/engine_spec.h"
#include "model/scene.h"
#include "output/position_stream.h"
#include "run/step_observer.h"

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace chainbench {

struct ReplayTrack {
  ReplayTrack(EngineSpec s, PositionStream p) : spec(std::move(s)), positions(std::move(p)) {}

  EngineSpec spec;
  PositionStream positions;
  // Per state (0 = as built, then one per step): energy-free displacement of the step into it,
  // summed over the dynamic bodies (m); the deepest overlap of any two boxes in it (m); and the
  // distance of the dynamic bodies' centres from the reference's, largest and root mean square
  // (m; empty without a reference). And the wall time of the step into it (ms; NaN for state 0,
  // which no step led to).
  std::vector<double> efd, penetration, error_max, error_rms, ms;
  struct Event {
    int step;
    std::string kind;
    std::size_t body;
  };
  std::vector<Event> events;  // the engine's events (engine.h), at most kMaxEvents
  std::uint64_t events_left_out = 0;
  struct Counted {
    std::string name, help;
    std::vector<std::pair<int, double>> steps;  // (step, value) where the value was not 0
  };
  std::vector<Counted> counted;  // the engine's counters that add up events (Aggregate::kSum)
  std::vector<int> degraded;     // the steps it cut short

  static constexpr std::size_t kMaxEvents = 20'000;
};

class ReplayRecorder final : public StepObserver {
 public:
  // `reference`: the engine the error series measures from (its run must come first), or none.
  ReplayRecorder(const Scene& scene, std::optional<EngineSpec> reference);
  void begin(const EngineSpec& spec, std::span<const CounterDef> counters) override;
  void observe(const StepView& view) override;

  double quantum() const { return quantum_; }
  const std::vector<ReplayTrack>& tracks() const { return tracks_; }
  const std::optional<EngineSpec>& reference() const { return reference_; }

 private:
  const Scene& scene_;
  std::optional<EngineSpec> reference_;
  double quantum_;
  double initial_depth_;
  std::vector<std::size_t> counted_;  // indices of the current engine's kSum counters
  std::vector<ReplayTrack> tracks_;
  std::vector<std::vector<Vec2d>> reference_states_;  // per state, while the reference records
  std::vector<Vec2d> shown_;  // per body: the centre stored for it last (bodies that come and go)
};

}  // namespace chainbench
