// Force-static propagation. Once a chain meets something immovable, the body it pushed acts as a
// wall: every dynamic body it now overlaps on its free side along the chaining axis is pushed
// fully out of it, is supported from that side, and becomes a wall in turn, breadth first, so
// lower walls settle before higher ones. A body between a wall and the wall's own support is not
// pushed into that support: if it rests there itself, the wall rests on it instead (yields). A
// wall pressed against an immovable body, or against a supported one on its free side, is crushed.
// Walls never move back for what they push, so a whole wall subtree needs no stack, and walls
// from many roots can propagate together: from every body resting on the ground at once, a pile
// is settled layer by layer, each layer a band of bodies close in memory.
#pragma once

#include "chain_state.h"
#include "step_context.h"

#include <cstdint>
#include <vector>

namespace chain::detail {

class ForceStatic {
 public:
  // A wall to propagate from: `body` was just placed against `wall` along `axis` (or leans on
  // it), backed in direction `backing` by the immovable body `anchor`; `depth`, its chain depth.
  struct Root {
    std::uint32_t body, wall;
    int axis, backing;
    std::uint32_t anchor, depth;
  };
  // Queues a root; run() propagates from every root queued since the last run, breadth first.
  void add(const Root& root) {
    queue_.push_back({root.body, root.wall, root.depth, root.anchor,
                      static_cast<std::int8_t>(root.axis), static_cast<std::int8_t>(root.backing)});
  }
  void run(StepContext& ctx, ChainState& state);

 private:
  struct Item {
    std::uint32_t body, wall, depth, anchor;
    std::int8_t axis, backing;
  };
  // Centres item.body between its wall and an immovable body beyond it, if there is one.
  void crush_check(StepContext& ctx, ChainState& state, const Item& item);
  // Moves wall w away from c, which lies on w's supported side and is supported there too; false
  // when a body beyond w stopped it short.
  bool yield(StepContext& ctx, ChainState& state, std::uint32_t w, std::uint32_t c, int axis);

  std::vector<Item> queue_;
  std::vector<std::uint32_t> cands_;
};

}  // namespace chain::detail
