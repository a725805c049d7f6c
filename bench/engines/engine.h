// One interface over both engines: build from a scene and a spec, step, read the state back.
// A call per step, never per body: the adapters keep their own state in their engine's layout.
#pragma once

#include "engine_spec.h"
#include "scene.h"

#include <chain/types.h>

#include <memory>
#include <span>
#include <vector>

namespace chainbench {

// Positions, velocities and angles of every body, in scene order.
struct BodyState {
  std::vector<Vec2d> position;
  std::vector<Vec2d> velocity;
  std::vector<double> angle;  // all zero unless the scene rotates

  explicit BodyState(std::size_t n = 0) : position(n), velocity(n), angle(n, 0.0) {}
};

class Engine {
 public:
  virtual ~Engine() = default;
  // Applies the drivers active at scene step `step_index`, then advances one scene step.
  virtual void step(int step_index) = 0;
  virtual void read_state(BodyState& out) const = 0;
  // The chaining solver's counters for the last step; null for an engine that has none.
  virtual const chain::StepStats* chain_stats() const { return nullptr; }
};

// Throws InputError when the scene asks for something the engine cannot do.
std::unique_ptr<Engine> make_engine(const EngineSpec& spec, const Scene& scene);

}  // namespace chainbench
