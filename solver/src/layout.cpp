// SPDX-License-Identifier: MIT
#include "layout.h"

#include <algorithm>
#include <cassert>

namespace chain::detail {
namespace {

// Renumber once more than one body in this many was reached by a jump in memory. A pile in
// Z-order has about one in six jumps back; a layer-by-layer walk over Z-ordered pyramids or stacks
// jumps forward over the other layers at most bodies; the order a resting pile was renumbered in
// has none.
constexpr std::size_t kJumpShare = 16;

}  // namespace

void Layout::reset(std::size_t bodies) {
  order_.reserve(bodies);
  placed_.assign(bodies, 0);
  spare_.reserve(bodies);
}

std::span<const std::uint32_t> Layout::plan(const Bodies& bodies,
                                            std::span<const std::uint32_t> reached,
                                            std::size_t jumps) {
  if (jumps * kJumpShare <= bodies.size()) return {};
  // The reached bodies in the order reached, the other dynamic bodies as they were, and the
  // immovable ones where they are (slot ranges by kind hold).
  order_.clear();
  std::fill(placed_.begin(), placed_.end(), std::uint8_t{0});
  for (const std::uint32_t body : reached) {
    assert(body < bodies.dynamic_end && !placed_[body]);
    placed_[body] = 1;
    order_.push_back(body);
  }
  for (std::uint32_t slot = 0; slot < bodies.size(); ++slot) {
    if (!placed_[slot]) order_.push_back(slot);
  }
  return order_;
}

}  // namespace chain::detail
