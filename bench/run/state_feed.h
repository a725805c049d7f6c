// SPDX-License-Identifier: MIT
// An engine's state before and after each step the harness looks at, read so that what a step
// left unchanged costs nothing to copy. Where the engine lists what changed
// (Engine::read_changes), only those bodies are copied into the state before the next step and
// read into the state after it; otherwise the whole state is read.
#pragma once

#include "engines/engine.h"

#include <cstdint>
#include <vector>

namespace chainbench {

class StateFeed {
 public:
  StateFeed(const Engine& engine, std::size_t bodies);

  // Reads the engine's state now: before() becomes what after() held, and after() the state now.
  // The first read leaves both holding the state now.
  void read();
  const BodyState& before() const { return before_; }
  const BodyState& after() const { return after_; }
  // The bodies whose position, velocity or angle differs between before() and after(), ascending;
  // null when the engine does not say.
  const std::vector<std::uint32_t>* changed() const { return known_ ? &changed_ : nullptr; }

 private:
  const Engine& engine_;
  BodyState before_, after_;
  std::vector<std::uint32_t> changed_;
  bool started_ = false;
  bool known_ = false;   // changed_ lists where before_ and after_ differ
  bool listing_ = true;  // the engine lists its changes (until it says it does not)
};

}  // namespace chainbench
