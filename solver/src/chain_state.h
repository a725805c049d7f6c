// State the modern resolver's chains share within a step: which bodies a chain has reached,
// which are supported by the immovable level (and from which side), which are crushed, the near
// pairs of the sweep, and the flags that say whether another sweep is needed.
#pragma once

#include "step_context.h"

#include <cstdint>
#include <vector>

namespace chain::detail {

struct Pair {
  std::uint32_t a, b;
};

class ChainState {
 public:
  // Sizes per-body marks; call at the start of every step.
  void begin_step(StepContext& ctx);
  // Forgets supports (bodies move between sweeps); with `near_pairs`, takes new near pairs.
  void begin_sweep(const Bodies& bodies, const std::vector<Pair>* near_pairs);
  // A fresh mark for the next chain.
  void begin_chain();

  // Appends to `out` every body that now overlaps `around`: from its near pairs while no body has
  // moved half the broadphase slack since the sweep began, else from the grid.
  void gather_overlaps(StepContext& ctx, std::uint32_t around,
                       std::vector<std::uint32_t>& out) const;

  // Direction in which c is pushed out of `from` along axis (+1 or -1).
  static int away(const StepContext& ctx, int axis, std::uint32_t from, std::uint32_t c) {
    const double* p = axis == 0 ? ctx.bodies.x.data() : ctx.bodies.y.data();
    return p[c] >= p[from] ? 1 : -1;
  }
  bool supported_towards(int axis, std::uint32_t body, int direction) const {
    return support_[axis][body] == direction;
  }
  std::uint32_t support_anchor(std::uint32_t body) const { return support_anchor_[body]; }
  void support(int axis, std::uint32_t body, int direction, std::uint32_t anchor) {
    support_[axis][body] = static_cast<std::int8_t>(direction);
    support_anchor_[body] = anchor;
  }

  bool visited(std::uint32_t body) const { return visited_[body] == stamp_; }
  void visit(std::uint32_t body) { visited_[body] = stamp_; }
  // Bodies held by frames still open (they follow back when their frame closes).
  std::uint32_t& on_stack(std::uint32_t body) { return on_stack_[body]; }
  std::uint32_t on_stack(std::uint32_t body) const { return on_stack_[body]; }

  bool crushed(std::uint32_t body) const { return crushed_[body] == step_; }
  // Reports `body` squeezed between `anchor` and `blocker` and leaves it alone for the step.
  void report_crush(StepContext& ctx, std::uint32_t body, std::uint32_t anchor,
                    std::uint32_t blocker, int axis);

  // Takes a pair resolution from the step's budget; false (and the chain cut) when none is left.
  bool spend(StepContext& ctx) {
    if (ctx.budget == 0) {
      cut = true;
      return false;
    }
    --ctx.budget;
    ++ctx.stats.resolve_calls;
    return true;
  }

  bool leftover = false;  // a chain left an overlap behind: the next sweep must look again
  bool cut = false;       // the current chain ran out of budget

 private:
  std::vector<std::uint32_t> near_start_, near_;  // near pairs as adjacency lists
  std::vector<std::uint32_t> visited_;            // stamp of the last chain a body joined
  std::uint32_t stamp_ = 0;
  std::vector<std::uint32_t> on_stack_;
  std::vector<std::uint32_t> crushed_;  // the step a body was crushed in
  std::uint32_t step_ = 0;
  std::vector<std::int8_t> support_[2];        // per axis: direction a body is backed in, or 0
  std::vector<std::uint32_t> support_anchor_;  // the immovable body behind that support
};

}  // namespace chain::detail
