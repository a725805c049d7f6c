// Force-static propagation. Once a chain meets something immovable, the body it pushed acts as a
// wall: every dynamic body it now overlaps on its free side along the chaining axis is pushed
// fully out of it, is supported from that side, and becomes a wall in turn, breadth first, so
// lower walls settle before higher ones. A body between a wall and the wall's own support is not
// pushed into that support: if it rests there itself, the wall rests on it instead (yields). A
// wall pressed against an immovable body, or against a supported one on its free side, is crushed.
// Walls never move back for what they push, so a whole wall subtree needs no stack.
#pragma once

#include "chain_state.h"
#include "step_context.h"

#include <cstdint>
#include <vector>

namespace chain::detail {

class ForceStatic {
 public:
  // `root` was just placed against `wall` along axis (or leans on it) and is backed in direction
  // `backing`; `depth` is the chain depth of root, for the statistics.
  void propagate(StepContext& ctx, ChainState& state, std::uint32_t root, std::uint32_t wall,
                 int axis, int backing, std::uint32_t anchor, std::uint32_t depth);

 private:
  struct Item {
    std::uint32_t body, wall, depth;
    int backing;
  };
  // Centres `body` between `wall` and an immovable body beyond it on `side`, if there is one.
  void crush_check(StepContext& ctx, ChainState& state, const Item& item, int axis,
                   std::uint32_t anchor);
  // Moves wall w away from c, which lies on w's supported side and is supported there too.
  void yield(StepContext& ctx, ChainState& state, std::uint32_t w, std::uint32_t c, int axis);

  std::vector<Item> queue_;
  std::vector<std::uint32_t> cands_;
};

}  // namespace chain::detail
