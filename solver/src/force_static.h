// SPDX-License-Identifier: MIT
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

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>
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
  // Call at the start of every step (squeezes are remembered from one step to the next).
  void begin_step(std::size_t bodies);
  // The slots were renumbered: forgets which bodies were squeezed.
  void forget_slots();
  // Some row was squeezed this step or the last: the next step reads what this one remembered.
  bool remembers_squeezes() const { return squeezes_ != 0; }
  // Body was in a squeezed row this step, the last or the one before: the steps it begins read
  // a squeeze they may not read again, so they are not its fixed point (islands.h).
  bool squeezed_lately(std::uint32_t body) const {
    return body < squeezed_.size() && squeezed_[body] != 0 && squeezed_[body] + 2 >= step_;
  }
  // What a step changes of the squeezes, to be undone when that step is solved again (a step
  // that skipped resting islands and met one): mark() before it, then undo() or keep().
  void mark();
  void undo();
  void keep() {
    marked_.on = false;
    undo_.clear();
  }
  // How deep a placed against b along axis stays: the overlap they had when the step began when
  // both were in a squeezed row the step before (a crushed row keeps its squeeze, and the step
  // adds only what it closes), else 0.
  double kept_squeeze(const StepContext& ctx, std::uint32_t a, std::uint32_t b, int axis) const {
    if (!squeezes_ || !squeezed_before(ctx, a) || !squeezed_before(ctx, b)) return 0.0;
    const int v = 1 - axis;
    const Bodies& bodies = ctx.bodies;
    const double across = (bodies.half(v, a) + bodies.half(v, b)) -
                          std::abs(bodies.start_pos(v, a) - bodies.start_pos(v, b));
    if (across <= ctx.def.touch_tolerance) return 0.0;
    return std::max(0.0, (bodies.half(axis, a) + bodies.half(axis, b)) -
                             std::abs(bodies.start_pos(axis, a) - bodies.start_pos(axis, b)));
  }

 private:
  struct Item {
    std::uint32_t body, wall, depth, anchor;
    std::int8_t axis, backing;
  };
  // What run() does after between(): the next candidate, none (the budget ran out), or the
  // candidates again from the first (w moved).
  enum class Between { kNext, kStop, kAgain };
  // Wall w meets c on its backed side (between w and its support), overlapping by `depth` along
  // axis: w rests on c when c is supported there too (yields).
  Between between(StepContext& ctx, ChainState& state, std::uint32_t w, std::uint32_t c, int axis,
                  double depth);
  // Centres item.body between its wall and an immovable body beyond it, if there is one.
  void crush_check(StepContext& ctx, ChainState& state, const Item& item);
  // Moves wall w away from c, which lies on w's supported side and is supported there too; false
  // when a body beyond w stopped it short.
  bool yield(StepContext& ctx, ChainState& state, std::uint32_t w, std::uint32_t c, int axis);

  // Wall item.body meets c, on its free side (dir) and supported from beyond: a squeeze. Squeezes
  // the row through them (or, when it cannot be traced, reports item.body crushed) and returns
  // true; false when a body between them ends this side's row, to be met from there.
  bool squeeze(StepContext& ctx, ChainState& state, const Item& item, std::uint32_t c, int dir);
  // Collects into `out` the walls of this chain from `from` back along axis, each to the one it
  // was placed against, and returns the immovable body they lead to (kNoSlot if they do not).
  std::uint32_t walls_back(const StepContext& ctx, const ChainState& state, std::uint32_t from,
                           int axis, std::vector<std::uint32_t>& out) const;
  // A row of walls (row_, from the anchor's side) squeezed between two immovable bodies takes
  // the squeeze evenly: every contact along it, the two end faces included, overlaps by the same
  // depth, and every body of the row is reported crushed. A squeeze taken at one contact grows
  // step after step there while a converging pair of walls closes in, until the boxes at that
  // contact pass each other; spread over the row it grows by the walls' closing over the number
  // of contacts, and no box passes another. False (nothing moved) when row_ is not in order.
  bool squeeze_row(StepContext& ctx, ChainState& state, std::uint32_t anchor, std::uint32_t blocker,
                   int axis);

  std::vector<Item> queue_;
  SlotList cands_;
  // An immovable body counts as squeezed: it is the end of every row.
  bool squeezed_before(const StepContext& ctx, std::uint32_t body) const {
    return ctx.bodies.immovable(body) || squeezed_[body] + 1 >= step_;
  }

  std::vector<std::uint32_t> against_;   // per slot: the body a wall was placed against
  std::vector<std::uint32_t> squeezed_;  // per slot: the last step it was in a squeezed row
  struct Marked {
    std::uint32_t step, squeezes, rows;
    bool on = false;
  } marked_;
  std::vector<std::pair<std::uint32_t, std::uint32_t>>
      undo_;  // (slot, squeezed_ before), since mark()
  std::uint32_t step_ = 1;
  std::uint32_t squeezes_ = 0;  // rows squeezed this step and the last
  std::uint32_t rows_ = 0;      // rows squeezed this step
  std::vector<std::uint32_t> row_;
};

}  // namespace chain::detail
