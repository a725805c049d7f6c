// SPDX-License-Identifier: MIT
#include "run/state_feed.h"

#include <utility>

namespace chainbench {

StateFeed::StateFeed(const Engine& engine, std::size_t bodies)
    : engine_(engine), before_(bodies), after_(bodies) {}

void StateFeed::read() {
  if (!started_) {
    engine_.read_state(after_);
    before_ = after_;
    changed_.clear();
    started_ = true;
    known_ = true;
    return;
  }
  if (listing_ && known_) {
    // before_ and after_ differ only where the last read changed them: copying those makes
    // before_ the state after() held, and leaves after_ as the engine last wrote it.
    for (const std::uint32_t i : changed_) {
      before_.position[i] = after_.position[i];
      before_.velocity[i] = after_.velocity[i];
      before_.angle[i] = after_.angle[i];
    }
    if (engine_.read_changes(after_, changed_)) return;
    listing_ = false;
  }
  std::swap(before_, after_);
  engine_.read_state(after_);
  known_ = false;
}

}  // namespace chainbench
