// SPDX-License-Identifier: MIT
// State the modern resolver's chains share within a step: which bodies a chain has reached,
// which are supported by the immovable level (and from which side), which are crushed, the near
// pairs of the pass, the flags that say whether another pass is needed, and the order in which
// the step first reached each body (layout.h renumbers the bodies by it).
#pragma once

#include "box_overlap.h"
#include "slot_list.h"
#include "step_context.h"

#include <cstdint>
#include <span>
#include <type_traits>
#include <vector>

namespace chain::detail {

struct Pair {
  std::uint32_t a, b;
};

class ChainState {
 public:
  // Sizes per-body marks; call at the start of every step.
  void begin_step(StepContext& ctx);
  // Forgets every per-body mark: the slots were renumbered.
  void forget_slots();
  // Forgets supports (bodies move between passes); with `near_pairs`, takes new near pairs.
  void begin_pass(const Bodies& bodies, const std::vector<Pair>* near_pairs);
  // A fresh mark for the next chain.
  void begin_chain();

  // Appends to `out` every body that now overlaps `around`, in slot order: from its near pairs
  // and the bodies the broadphase filed again since they were taken, or, when `around` itself was
  // filed again, from the grid; the same list whichever way. True when one of them is immovable.
  // What it met is charged to the budget (StepContext::charge_met). Inline: every body a chain
  // reaches takes it.
  template <class Out>
  bool gather_overlaps(StepContext& ctx, std::uint32_t around, Out& out) const {
    return gather_overlaps(ctx, around, out, OverlapTest(ctx.def.touch_tolerance));
  }
  // The same with the test's constants made by the caller, once for many walks.
  template <class Out>
  bool gather_overlaps(StepContext& ctx, std::uint32_t around, Out& out,
                       const OverlapTest& test) const {
    const std::size_t before = out.size();
    if (!ctx.broadphase.near_pairs_hold() && ctx.broadphase.near_stale(around)) [[unlikely]] {
      const bool immovable = gather_overlaps_refiled(ctx, around, out);
      ctx.charge_met(around, out.size() - before);
      return immovable;
    }
    // Every body that moved less than the broadphase's refile distance since the near pairs were
    // taken closed by less than the slack with any other such body: every one of them that
    // overlaps `around` now is among its near pairs. A body filed again since was filed too far
    // from `around` to overlap it (near_stale), or `around` would take the path above: its near
    // list is the whole answer still.
    const std::span<const std::uint32_t> list = near(around);
    const std::uint32_t dynamic_end = ctx.bodies.dynamic_end;
    bool immovable = false;
    if constexpr (std::is_same_v<Out, SlotList>) out.room_for(list.size());
    for_each_hit(ctx.bodies.box.data(), around, list, test, [&](std::uint32_t j) {
      if constexpr (std::is_same_v<Out, SlotList>) {
        out.push(j);
      } else {
        out.push_back(j);
      }
      immovable |= j >= dynamic_end;
    });
    ctx.charge_met(around, out.size() - before);
    return immovable;
  }
  // gather_overlaps once some body was filed again since the near pairs were taken.
  bool gather_overlaps_refiled(StepContext& ctx, std::uint32_t around,
                               std::vector<std::uint32_t>& out) const;
  bool gather_overlaps_refiled(StepContext& ctx, std::uint32_t around, SlotList& out) const;

  // Direction in which c is pushed out of `from` along axis (+1 or -1).
  static int away(const StepContext& ctx, int axis, std::uint32_t from, std::uint32_t c) {
    return ctx.bodies.pos(axis, c) >= ctx.bodies.pos(axis, from) ? 1 : -1;
  }
  // The side of `from` that c was on along axis when the step began, or, when they started level
  // (within the touch tolerance), is on now. A wall placed against its own wall may land on or
  // past the middle of the next body of its chain; that body is still pushed on the side it was on.
  static int side_at_start(const StepContext& ctx, int axis, std::uint32_t from, std::uint32_t c) {
    // Both dynamic here (walls and what they push): their start positions are stored.
    const Point& a = ctx.bodies.start[from];
    const Point& b = ctx.bodies.start[c];
    const double d = axis == 0 ? b.x - a.x : b.y - a.y;
    if (std::abs(d) <= ctx.def.touch_tolerance) return away(ctx, axis, from, c);
    return d > 0.0 ? 1 : -1;
  }
  bool supported_towards(int axis, std::uint32_t body, int direction) const {
    const Marks& m = marks_[body];
    return m.support_pass == pass_ && m.support_dir[axis] == direction;
  }
  std::uint32_t support_anchor(std::uint32_t body) const { return marks_[body].support_anchor; }
  void support(int axis, std::uint32_t body, int direction, std::uint32_t anchor) {
    Marks& m = marks_[body];
    if (m.support_pass != pass_) {  // supports of earlier passes no longer hold
      m.support_pass = pass_;
      m.support_dir[0] = m.support_dir[1] = 0;
    }
    m.support_dir[axis] = static_cast<std::int8_t>(direction);
    m.support_anchor = anchor;
  }
  // Near lists hold entries, slot * kEntryScale (box_overlap.h); entry_slot() gives the slot.
  static std::uint32_t entry_slot(std::uint32_t entry) { return entry / kEntryScale; }
  // Where near(body) starts among all the near lists, which lie end to end in slot order.
  std::uint32_t near_offset(std::uint32_t body) const { return near_start_[body]; }
  // The bodies that were near `body` when the near pairs were last taken, as entries.
  std::span<const std::uint32_t> near(std::uint32_t body) const {
    return {near_.data() + near_start_[body], near_.data() + near_start_[body + 1]};
  }
  // The same (entries too), less the bodies of higher slots: a pair is taken at its later body
  // (gather_contacts) without reading the other half of the list. Where lower(body) starts among
  // them all, in slot order.
  std::span<const std::uint32_t> lower(std::uint32_t body) const {
    return {lower_.data() + lower_start_[body], lower_.data() + lower_start_[body + 1]};
  }
  std::uint32_t lower_offset(std::uint32_t body) const { return lower_start_[body]; }

  bool visited(std::uint32_t body) const { return marks_[body].visited == stamp_; }
  void visit(std::uint32_t body) {
    reach(body);
    marks_[body].visited = stamp_;
  }
  // Bodies this chain placed as walls along axis: another wall of the chain may push them further.
  bool walled(std::uint32_t body, int axis) const {
    return marks_[body].walled == stamp_ && marks_[body].walled_axis == axis;
  }
  void wall(std::uint32_t body, int axis) {
    reach(body);
    marks_[body].visited = marks_[body].walled = stamp_;
    marks_[body].walled_axis = static_cast<std::int8_t>(axis);
  }
  // wall(body, axis), then support(axis, body, direction, anchor): the walls' loop does both for
  // every body it places.
  void wall_supported(std::uint32_t body, int axis, int direction, std::uint32_t anchor) {
    reach(body);
    Marks& m = marks_[body];
    m.visited = m.walled = stamp_;
    m.walled_axis = static_cast<std::int8_t>(axis);
    if (m.support_pass != pass_) {
      m.support_pass = pass_;
      m.support_dir[0] = m.support_dir[1] = 0;
    }
    m.support_dir[axis] = static_cast<std::int8_t>(direction);
    m.support_anchor = anchor;
  }
  // Bodies held by frames still open (they follow back when their frame closes).
  std::uint32_t& on_stack(std::uint32_t body) { return marks_[body].on_stack; }
  std::uint32_t on_stack(std::uint32_t body) const { return marks_[body].on_stack; }

  bool crushed(std::uint32_t body) const {
    return marks_[body].reached == step_ && marks_[body].crushed;
  }
  // Reports `body` squeezed between `anchor` and `blocker` (once a step) and leaves it alone for
  // the step.
  void report_crush(StepContext& ctx, std::uint32_t body, std::uint32_t anchor,
                    std::uint32_t blocker, int axis);

  // Takes a pair resolution from the step's budget for a chain through `body`; false (and the
  // chain cut) when none is left.
  bool spend(StepContext& ctx, std::uint32_t body) {
    if (ctx.budget == 0) {
      cut = true;
      return false;
    }
    --ctx.budget;
    if (ctx.spent != nullptr) ++ctx.spent[body];
    ++ctx.stats.resolve_calls;
    return true;
  }

  // A chain left an overlap behind, involving these bodies: the next pass looks at them again.
  void flag(std::uint32_t body) {
    leftover = true;
    if (marks_[body].suspect != suspect_stamp_) {
      marks_[body].suspect = suspect_stamp_;
      suspects_.push_back(body);
    }
  }
  void flag(std::uint32_t a, std::uint32_t b) {
    flag(a);
    flag(b);
  }
  bool suspect(std::uint32_t body) const { return marks_[body].suspect == suspect_stamp_; }
  // The bodies flagged since the pass began, each once.
  const std::vector<std::uint32_t>& suspects() const { return suspects_; }
  void clear_suspects();

  // Dynamic bodies in the order the step first reached them, and how many of them were not just
  // ahead of the body reached before (a jump back in memory, or forward past kNearSlots): each
  // such starts a new run of memory, where a walk front to back continues the one it is in.
  // Counted when asked, in one vectorised pass over the order: the layout asks only once
  // Layout::kMinSteps steps have passed since it last renumbered, and counted at every reach the
  // test cost every placed body about eight instructions.
  std::span<const std::uint32_t> reach_order() const { return reach_order_; }
  std::size_t reach_jumps() const;
  // A body reached at most this many slots after the one before continues its run: the lines it
  // needs are those the walk just read, or the next few, which the hardware prefetches.
  static constexpr std::uint32_t kNearSlots = 8;

  bool leftover = false;  // some chain flagged a body: the next pass must look again
  bool cut = false;       // the current chain ran out of budget

 private:
  // Everything a chain reads and writes about one body, together: a chain jumps from body to
  // body, and one cache line then serves two bodies instead of one line per array.
  struct Marks {
    std::uint32_t visited = 0;  // stamp of the last chain the body joined
    std::uint32_t walled = 0;   // stamp of the last chain that placed it as a wall
    std::uint32_t on_stack = 0;
    std::uint32_t reached = 0;               // the last step a chain reached it in
    std::uint32_t support_pass = 0;          // the pass its supports were found in
    std::uint32_t support_anchor = kNoSlot;  // the immovable body behind its supports
    std::uint32_t suspect = 0;               // stamp of the pass that flagged it
    std::int8_t support_dir[2] = {0, 0};     // per axis: the direction it is backed in, or 0
    std::int8_t walled_axis = 0;
    bool crushed = false;  // crushed in step `reached`
  };

  void reach(std::uint32_t body) {
    Marks& m = marks_[body];
    if (m.reached == step_) return;
    m.reached = step_;
    m.crushed = false;
    reach_order_.push_back(body);
  }

  std::vector<std::uint32_t> near_start_, near_;    // near pairs as adjacency lists
  std::vector<std::uint32_t> lower_start_, lower_;  // their entries of lower slots
  std::vector<Marks> marks_;
  std::uint32_t stamp_ = 0;
  std::uint32_t step_ = 0;
  std::uint32_t pass_ = 0;
  std::vector<std::uint32_t> suspects_;
  mutable std::vector<std::uint32_t> refiled_;  // gather_overlaps_refiled's list for a SlotList
  std::uint32_t suspect_stamp_ = 1;
  std::vector<std::uint32_t> reach_order_;  // each body at most once a step: capacity n
};

}  // namespace chain::detail
