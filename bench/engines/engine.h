// SPDX-License-Identifier: MIT
// One interface over every engine: built from a scene and a spec (registry.h), stepped, read back.
// A call per step, never per body: adapters keep their own state in their engine's layout.
#pragma once

#include "model/scene.h"

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace chainbench {

// Positions, velocities and angles of every body, in scene order.
struct BodyState {
  std::vector<Vec2d> position;
  std::vector<Vec2d> velocity;
  std::vector<double> angle;  // all zero unless the scene rotates

  explicit BodyState(std::size_t n = 0) : position(n), velocity(n), angle(n, 0.0) {}
};

// How a counter's per-step values add up over a run, as Google Benchmark's user counters do.
enum class Aggregate : std::uint8_t {
  kMean,  // per step on average: contacts, pair resolutions
  kSum,   // over the run: events
  kMax,   // the largest of any step: depths
  kLast,  // the last step's: a size the engine has reached
};

// A counter's running figure after a step that reported `value` (a mean is a sum until the end).
inline double aggregate_step(Aggregate aggregate, double total, double value) {
  if (aggregate == Aggregate::kMax) return total > value ? total : value;
  if (aggregate == Aggregate::kLast) return value;
  return total + value;
}

// A figure an engine reports about each step, which the harness aggregates without knowing what
// it means.
struct CounterDef {
  std::string name;  // in JSON, CSV and benchmark counters: "contacts", "budget_hits"
  Aggregate aggregate = Aggregate::kMean;
  std::string help;
  std::string column;  // its title in `run`'s table, or empty to leave it to the JSON
  friend bool operator==(const CounterDef&, const CounterDef&) = default;
};

// A body that one of the engine's events of the last step concerns (a crush names the body
// squeezed), by scene index; `kind` is a short name the engine gives its events.
struct EngineEvent {
  const char* kind = "";
  std::size_t body = 0;
};

// A stage of an engine's step and its wall time in the last step, as the engine itself measures
// it (Box2D's b2Profile, the chain solver's StepProfile).
struct StageTime {
  const char* name = "";
  double ms = 0.0;
};

class Engine {
 public:
  virtual ~Engine() = default;
  // Applies the drives the scene holds at step `step_index` (DriveSchedule), then advances one
  // scene step.
  virtual void step(int step_index) = 0;
  // Writes every body in the world; the entries of bodies not in it are left as they were.
  virtual void read_state(BodyState& out) const = 0;
  // Bodies that come and go (SceneBody::from_step): an engine is built with the bodies of state 0;
  // the runner adds body `index` after step from_step - 1 (before state from_step is read) and
  // removes it before step to_step, both in the timed step (a game pays for them), in scene order.
  // An added body is as the scene describes it (centre, velocity).
  virtual void add_body(std::size_t index) = 0;
  virtual void remove_body(std::size_t index) = 0;
  // Where the engine can tell what changed: brings `state`, which holds what this engine's last
  // read_state() or read_changes() wrote, up to its state now, lists in `changed` (ascending)
  // every body whose position, velocity or angle differs, and returns true. The default returns
  // false and writes nothing: the caller then reads the whole state.
  virtual bool read_changes(BodyState& state, std::vector<std::uint32_t>& changed) const {
    (void)state, (void)changed;
    return false;
  }
  // What the engine counts about each step, and the last step's values in that order.
  virtual std::span<const CounterDef> counter_defs() const { return {}; }
  virtual std::span<const double> counters() const { return {}; }
  // Whether the engine cut the last step short to bound its work: the run is then `budget`.
  virtual bool degraded() const { return false; }
  // The bodies the last step's events concern (replay pages mark them); none by default.
  virtual std::span<const EngineEvent> events() const { return {}; }
  // Asks the engine to time the stages of the steps that follow (`chainbench run --profile`).
  virtual void measure_stages() {}
  // The last step's stage times, top-level stages in the engine's order, the same names every
  // step; empty for an engine that measures none (the default) or was not asked to.
  virtual std::span<const StageTime> stages() const { return {}; }
};

}  // namespace chainbench
