// SPDX-License-Identifier: MIT
// Which drives a scene holds at each step, decided once here so that every engine applies the
// same ones: per driven body, the last of its drivers active at that step wins.
//
// The schedule follows what changes: its drivers' starts and ends are sorted by step once, and a
// step costs the drivers that start or end in it and the driven bodies, never every driver.
#pragma once

#include "model/scene.h"

#include <cstdint>
#include <span>
#include <vector>

namespace chainbench {

struct Drive {
  std::size_t body = 0;
  Vec2d velocity;
  bool hold_x = true;
  bool hold_y = true;
  friend bool operator==(const Drive&, const Drive&) = default;
};

class DriveSchedule {
 public:
  explicit DriveSchedule(const Scene& scene);
  // Moves to step n. Steps are taken in order (n one more than the last); a jump ahead costs the
  // events it passes, a step back every driven body. changed() and released() compare with the
  // step last advanced to (none before the first). Allocates nothing once built.
  void advance(int n);
  // The drives held at the step, at most one per body, in the order the bodies were first driven
  // (their first drivers' order in the scene): what an engine whose drives last one step applies.
  std::span<const Drive> active() const { return active_; }
  // The drives that begin at this step or differ from the body's drive at the step before, in the
  // same order: with released(), all that an engine whose drives persist (the chain solver's
  // set_drive) needs.
  std::span<const Drive> changed() const { return changed_; }
  // Bodies driven at the step before and free at this one, in the same order.
  std::span<const std::size_t> released() const { return released_; }

 private:
  struct Event {
    int step;
    std::uint32_t local;  // the body's index in bodies_
  };
  void settle(std::uint32_t local, int n);  // works out one body's drive at step n

  std::vector<Driver> drivers_;
  std::vector<std::size_t> bodies_;          // the driven bodies, each once, first driven first
  std::vector<std::uint32_t> first_driver_;  // per driven body: where its drivers start in order_
  std::vector<std::uint32_t> order_;         // driver indices grouped by body, ascending in each
  std::vector<Event> events_;                // starts and ends, by step then body
  std::vector<std::uint8_t> held_;           // per driven body: driven at the current step
  std::vector<Drive> current_;               // per driven body: its drive when held
  std::vector<std::uint32_t> dirty_;         // bodies with an event at this step, ascending
  std::vector<std::uint8_t> marked_;         // per driven body: in dirty_
  std::vector<Drive> active_, changed_;
  std::vector<std::size_t> released_;
  std::size_t next_event_ = 0;
  int step_ = -1;  // the step last advanced to
  bool membership_changed_ = true;
};

}  // namespace chainbench
