// Which drives a scene holds at each step, decided once here so that every engine applies the
// same ones: per driven body, the last of its drivers active at that step wins.
#pragma once

#include "scene.h"

#include <cstdint>
#include <span>
#include <vector>

namespace chainbench {

struct Drive {
  std::size_t body = 0;
  Vec2d velocity;
  bool hold_x = true;
  bool hold_y = true;
};

class DriveSchedule {
 public:
  explicit DriveSchedule(const Scene& scene);
  // Moves to step n (call once per step, in order). Allocates nothing.
  void advance(int n);
  // The drives held at the step, at most one per body, in the order the bodies were first driven.
  std::span<const Drive> active() const { return active_; }
  // Bodies driven at the step before and free at this one, for engines whose drives persist.
  std::span<const std::size_t> released() const { return released_; }

 private:
  std::vector<Driver> drivers_;
  std::vector<std::size_t> bodies_;   // the driven bodies, each once
  std::vector<std::uint32_t> local_;  // per driver: its body's index in bodies_
  std::vector<std::int32_t> slot_;    // per driven body: its place in active_, or -1
  std::vector<std::uint8_t> was_;     // per driven body: held at the step before
  std::vector<Drive> active_;
  std::vector<std::uint32_t> active_local_;  // per entry of active_: its body's index in bodies_
  std::vector<std::size_t> released_;
};

}  // namespace chainbench
