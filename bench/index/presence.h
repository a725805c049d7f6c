// SPDX-License-Identifier: MIT
// Which bodies are in the world in each state of a run (SceneBody::alive: body i is in states
// from_step..to_step), followed state by state at the cost of the bodies that enter or leave.
// The metrics, the trace and the replay page see a body only while it is in the world.
#pragma once

#include "model/scene.h"

#include <cstdint>
#include <span>
#include <vector>

namespace chainbench {

// Whether bodies a and b meet in state k: both are in it (SceneBody::alive), and they take part
// in a step together next to it. A body in its last state (to_step) and one in its first
// (from_step) never do: the runner removes the first before the step it would share with the
// second (lifetimes.h), so their boxes in that state are never in the world together.
inline bool meet(const SceneBody& a, const SceneBody& b, int k) {
  return a.alive(k) && b.alive(k) && !(a.to_step == k && b.from_step == k) &&
         !(b.to_step == k && a.from_step == k);
}

class Presence {
 public:
  // Stands at state 0.
  explicit Presence(const Scene& scene);
  // Whether some body enters after state 0 or leaves before the last state; when not, every body
  // is in every state and at() costs nothing.
  bool any() const { return any_; }
  // Moves to state k. Consecutive states cost the bodies that enter or leave between them; any
  // other move recomputes every body.
  void at(int k);
  int state() const { return state_; }
  // Body i is in the world in the state now (k), in the state before it (k - 1), and in both: it
  // took part in step k - 1, the step into the state now. At state 0 `was` is `in`.
  bool in(std::size_t i) const { return now_[i] != 0; }
  bool was(std::size_t i) const { return before_[i] != 0; }
  bool stepped(std::size_t i) const { return (now_[i] & before_[i]) != 0; }
  // Per body: 1 when in the world in the state now.
  std::span<const std::uint8_t> mask() const { return now_; }
  // The bodies that entered or left between state k - 1 and state k, ascending.
  std::span<const std::uint32_t> changed() const {
    return std::span<const std::uint32_t>(bodies_).subspan(first_, last_ - first_);
  }
  // How many dynamic bodies took part in the step into the state now.
  std::size_t dynamic_stepped() const { return dynamic_stepped_; }
  // How many bodies of any kind are in the world in the state now, and how many took part in the
  // step into it.
  std::size_t count() const { return count_; }
  std::size_t stepped_count() const { return stepped_; }

 private:
  void recompute(int k);
  const Scene& scene_;
  bool any_ = false;
  int state_ = 0;
  std::vector<std::uint8_t> now_, before_;
  // Every change of a body's presence, ordered by state then body: body bodies_[e] enters or
  // leaves between states states_[e] - 1 and states_[e]. changed() is [first_, last_).
  std::vector<int> states_;
  std::vector<std::uint32_t> bodies_;
  std::size_t first_ = 0, last_ = 0;
  std::size_t dynamic_now_ = 0, dynamic_stepped_ = 0, count_ = 0, stepped_ = 0;
};

}  // namespace chainbench
