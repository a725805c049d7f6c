// SPDX-License-Identifier: MIT
// When each body of a scene enters and leaves the world (SceneBody::from_step, to_step), decided
// once so that the runner and the benchmark add and remove the same bodies at the same steps.
#pragma once

#include "engines/engine.h"
#include "model/scene.h"

#include <cstdint>
#include <vector>

namespace chainbench {

class Lifetimes {
 public:
  explicit Lifetimes(const Scene& scene);
  // Whether any body comes or goes during the run.
  bool any() const { return !enter_.empty() || !leave_.empty(); }
  // Removes the bodies whose to_step is n (call before step n), in scene order.
  void leave(Engine& engine, int n) const;
  // Adds the bodies whose from_step is n (call after step n - 1, before state n is read, so that
  // state n shows them as the scene describes them), in scene order.
  void enter(Engine& engine, int n) const;
  // Both, before step n: what a game does between two frames.
  void apply(Engine& engine, int n) const {
    leave(engine, n);
    enter(engine, n);
  }

 private:
  struct Event {
    int step;
    std::uint32_t body;
  };
  static void run(const std::vector<Event>& events, std::size_t& next, int n, Engine& engine,
                  bool add);
  std::vector<Event> enter_, leave_;  // by step, then body
  mutable std::size_t next_enter_ = 0, next_leave_ = 0;
};

}  // namespace chainbench
