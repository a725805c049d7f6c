// SPDX-License-Identifier: MIT
#include "run/lifetimes.h"

#include <algorithm>
#include <tuple>

namespace chainbench {

Lifetimes::Lifetimes(const Scene& scene) {
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const SceneBody& b = scene.bodies[i];
    const auto body = static_cast<std::uint32_t>(i);
    // A body of state 0 is built with the engine; one that leaves after the last step never does.
    if (b.from_step > 0 && b.from_step <= scene.steps) enter_.push_back({b.from_step, body});
    if (b.to_step < scene.steps && b.from_step < scene.steps) leave_.push_back({b.to_step, body});
  }
  auto order = [](const Event& a, const Event& b) {
    return std::tie(a.step, a.body) < std::tie(b.step, b.body);
  };
  std::sort(enter_.begin(), enter_.end(), order);
  std::sort(leave_.begin(), leave_.end(), order);
}

void Lifetimes::run(const std::vector<Event>& events, std::size_t& next, int n, Engine& engine,
                    bool add) {
  // Steps come in order; a step skipped (a run started late) skips its events.
  while (next < events.size() && events[next].step < n)
    ++next;
  for (; next < events.size() && events[next].step == n; ++next) {
    if (add) {
      engine.add_body(events[next].body);
    } else {
      engine.remove_body(events[next].body);
    }
  }
}

void Lifetimes::leave(Engine& engine, int n) const {
  run(leave_, next_leave_, n, engine, false);
}

void Lifetimes::enter(Engine& engine, int n) const {
  run(enter_, next_enter_, n, engine, true);
}

}  // namespace chainbench
