// SPDX-License-Identifier: MIT
// When the bodies are renumbered after the first Z-order.
//
// canonicalize() puts bodies close in space close in memory, but not in the order a step visits
// them: the modern resolver settles a pile from the ground up, layer by layer, and one layer of a
// Z-ordered pile is spread over all of memory, so at a million bodies nearly every body it
// reaches is a cache miss. When a step reaches many bodies out of slot order, the dynamic bodies
// are renumbered in the order that step reached them, and the steps after it walk memory front
// to back. The reach order depends on the bodies alone, so a scene built in any order is
// renumbered the same way.
#pragma once

#include "bodies.h"

#include <cstdint>
#include <span>
#include <vector>

namespace chain::detail {

class Layout {
 public:
  // Renumber at most once in this many steps: renumbering costs about as much as a step, and a
  // scene whose reach order changes every step would otherwise pay for it every step.
  static constexpr std::uint32_t kMinSteps = 32;

  // Sizes every buffer for the body set, so that renumbering allocates nothing; call whenever
  // the body set changes. It does not restart the count of steps since the last renumbering, so
  // a world whose body set changes every step is still renumbered at most once in 32 steps.
  void reset(std::size_t bodies);
  // Call once after every step: true on every kMinSteps-th step, when plan() is to be asked. A
  // fixed schedule, whatever plan() answered before: a step that skips resting islands
  // (islands.h) cannot give plan() the reach order of the whole world, so the steps that ask are
  // known ahead (due_next()) and solved whole.
  bool due() {
    if (++steps_since_ < kMinSteps) return false;
    steps_since_ = 0;
    return true;
  }
  // Whether the next call of due() returns true.
  bool due_next() const { return steps_since_ + 1 >= kMinSteps; }
  // After a step that due() allowed and that first reached the dynamic bodies `reached` in that
  // order, with `jumps` jumps in memory (ChainState::reach_jumps): the order to renumber the
  // slots in (slot i takes the body of slot order[i]), or empty when the layout is good enough.
  std::span<const std::uint32_t> plan(const Bodies& bodies, std::span<const std::uint32_t> reached,
                                      std::size_t jumps);
  Bodies::Spare& spare() { return spare_; }

 private:
  std::vector<std::uint32_t> order_;
  std::vector<std::uint8_t> placed_;
  Bodies::Spare spare_;
  // Steps since plan() was last asked; the first step asks.
  std::uint32_t steps_since_ = kMinSteps - 1;
};

}  // namespace chain::detail
