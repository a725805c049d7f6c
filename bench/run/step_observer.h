// SPDX-License-Identifier: MIT
// What a run shows its observers after every step (the trace CSV, the replay page): the state,
// the harness' per-body measures of that step, and the engine's own counters and events. With no
// observer a run reads nothing it does not need; with one, it reads every step's state back.
#pragma once

#include "engines/engine.h"
#include "engines/engine_spec.h"

#include <cstdint>
#include <span>

namespace chainbench {

struct StepView {
  int step = 0;       // steps taken: 1 after the first
  double time = 0.0;  // step * dt, s
  const BodyState* state = nullptr;
  std::span<const double> displacement;  // per body: energy-free displacement of this step, m
  std::span<const double> penetration;   // per body: its deepest overlap after this step, m
  // Per body: 1 when it is in the world in this state (SceneBody::alive); empty when every body
  // is in every state. A body out of the world has no state: its entries in `state` are stale.
  std::span<const std::uint8_t> present;
  std::span<const double> counters;     // the engine's counters of this step (counter_defs order)
  std::span<const EngineEvent> events;  // the bodies the engine's events of this step concern
  bool degraded = false;                // the engine cut this step short
  double ms = 0.0;                      // the step's wall time on the steady clock, ms
};

class StepObserver {
 public:
  virtual ~StepObserver() = default;
  // A run of `spec` starts; `counters` names what StepView::counters will hold.
  virtual void begin(const EngineSpec& spec, std::span<const CounterDef> counters) = 0;
  virtual void observe(const StepView& view) = 0;
};

}  // namespace chainbench
