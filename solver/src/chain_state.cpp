// SPDX-License-Identifier: MIT
#include "chain_state.h"

#include "buffer.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <stdexcept>

namespace chain::detail {

void ChainState::begin_step(StepContext& ctx) {
  const std::size_t n = ctx.bodies.size();
  if (marks_.size() != n) {
    // The body set changed: size every per-body buffer for it now, not in some later step.
    resize_buffer(marks_, n);
    forget_slots();
    // The near lists themselves are sized by the scans that fill them (a row has two neighbours a
    // body, a pile six or more): a guess here held 48 bytes a body, most of them unused.
    reserve_buffer(near_start_, n + 2);
    reserve_buffer(lower_start_, n + 1);
    ctx.crushes.reserve(std::min<std::size_t>(n, 1024));
    refiled_.reserve(64);
  }
  // Each holds a body at most once; checked every step, as a copied world's vectors come without
  // the capacity of the original's.
  reserve_buffer(reach_order_, n);
  reserve_buffer(suspects_, n);
  if (++step_ == 0) {  // wrapped: forget every old mark
    for (Marks& m : marks_)
      m.reached = 0;
    step_ = 1;
  }
  reach_order_.clear();
  leftover = false;
}

void ChainState::forget_slots() {
  std::fill(marks_.begin(), marks_.end(), Marks{});
  stamp_ = step_ = pass_ = 0;
  suspect_stamp_ = 1;
  suspects_.clear();
  reach_order_.clear();
}

void ChainState::begin_pass(const Bodies& bodies, const std::vector<Pair>* near_pairs) {
  if (++pass_ == 0) {  // wrapped: forget every old support
    for (Marks& m : marks_)
      m.support_pass = 0;
    pass_ = 1;
  }
  if (!near_pairs) return;
  const std::uint32_t n = bodies.size();
  if (n > kMaxEntrySlots) throw std::length_error("chain: more bodies than near lists can hold");
  assign_buffer(near_start_, n + 2, 0);
  for (const Pair& p : *near_pairs)
    ++near_start_[p.a + 2], ++near_start_[p.b + 2];
  for (std::uint32_t i = 2; i < n + 2; ++i)
    near_start_[i] += near_start_[i - 1];
  resize_buffer(near_, near_start_[n + 1]);
  for (const Pair& p : *near_pairs) {  // near_start_[i + 1] is the fill cursor of body i
    near_[near_start_[p.a + 1]++] = p.b * kEntryScale;
    near_[near_start_[p.b + 1]++] = p.a * kEntryScale;
  }
  // Each list in slot order: the order a chain meets a body's overlaps in is then theirs alone,
  // not that of the scan's cells, so when the near pairs were scanned, and which bodies beyond
  // the overlapping ones they hold, changes no result.
  for (std::uint32_t i = 0; i < n; ++i)
    std::sort(near_.begin() + near_start_[i], near_.begin() + near_start_[i + 1]);
  // Each body's lower neighbours, in the order of its near list.
  resize_buffer(lower_start_, n + 1);
  resize_buffer(lower_, near_.size() / 2);
  std::uint32_t fill = 0;
  for (std::uint32_t i = 0; i < n; ++i) {
    lower_start_[i] = fill;
    for (std::uint32_t k = near_start_[i]; k < near_start_[i + 1]; ++k) {
      if (near_[k] < i * kEntryScale) lower_[fill++] = near_[k];
    }
  }
  lower_start_[n] = fill;
}

std::size_t ChainState::reach_jumps() const {
  // A layer-by-layer walk over a Z-ordered pile rarely goes back, but it skips forward over the
  // other layers' bodies: every layer is a sweep over all of memory, and at a million bodies
  // nearly every body it reaches is a cache miss. Jumps forward count as much as back.
  // A step back wraps around to more than kNearSlots in unsigned arithmetic: one test for both,
  // which the compiler vectorises.
  const std::uint32_t* const order = reach_order_.data();
  std::uint32_t jumps = 0;  // at most one a body: fits
  for (std::size_t k = 1; k < reach_order_.size(); ++k) {
    jumps += static_cast<std::uint32_t>(order[k] - order[k - 1]) > kNearSlots;
  }
  return jumps;
}

void ChainState::clear_suspects() {
  suspects_.clear();
  if (++suspect_stamp_ == 0) {
    for (Marks& m : marks_)
      m.suspect = 0;
    suspect_stamp_ = 1;
  }
}

void ChainState::begin_chain() {
  if (++stamp_ == 0) {  // wrapped: forget every old mark
    for (Marks& m : marks_)
      m.visited = m.walled = 0;
    stamp_ = 1;
  }
  cut = false;
}

// Kept out of gather_overlaps: the near-pair loop above runs for every body a chain reaches, and
// the broadphase queries here, inlined into it, slowed it by a tenth.
[[gnu::noinline]] bool ChainState::gather_overlaps_refiled(StepContext& ctx, std::uint32_t around,
                                                           std::vector<std::uint32_t>& out) const {
  const std::size_t from = out.size();
  const double tol = ctx.def.touch_tolerance;
  const Broadphase& bp = ctx.broadphase;
  const Bodies& b = ctx.bodies;
  const bool filters = !b.filter.empty();  // read once: the pushes below may reload it each time
  if (bp.stale(around)) {  // filed again since the near pairs were taken: they do not hold for it
    bp.for_each_overlap(b, around, tol, [&](std::uint32_t j) {
      if (!filters || b.collides(around, j)) out.push_back(j);
    });
    std::sort(out.begin() + static_cast<std::ptrdiff_t>(from), out.end());  // as near lists are
    return std::any_of(out.begin() + from, out.end(),
                       [&](std::uint32_t j) { return b.immovable(j); });
  }
  // Its near pairs, less the bodies filed again since, which the overlay then gives. The near
  // list goes through the walks' overlap test, and only its hits are checked for staleness: the
  // same bodies in the same order as testing staleness first, without reading the broadphase's
  // per-body marks for every entry.
  for_each_hit(b.box.data(), around, near(around), OverlapTest(tol), [&](std::uint32_t j) {
    if (!bp.stale(j)) out.push_back(j);
  });
  bp.for_each_stale_overlap(b, around, tol, [&](std::uint32_t j) {
    if (!filters || b.collides(around, j)) out.push_back(j);
  });
  // In slot order, as the near list alone would give them: the list's hits are, the overlay's
  // come after them in the overlay's order.
  std::sort(out.begin() + static_cast<std::ptrdiff_t>(from), out.end());
  return std::any_of(out.begin() + from, out.end(),
                     [&](std::uint32_t j) { return b.immovable(j); });
}

bool ChainState::gather_overlaps_refiled(StepContext& ctx, std::uint32_t around,
                                         SlotList& out) const {
  refiled_.clear();
  const bool immovable = gather_overlaps_refiled(ctx, around, refiled_);
  out.room_for(refiled_.size());
  for (const std::uint32_t j : refiled_)
    out.push(j);
  return immovable;
}

void ChainState::report_crush(StepContext& ctx, std::uint32_t body, std::uint32_t anchor,
                              std::uint32_t blocker, int axis) {
  assert(anchor != kNoSlot && blocker != kNoSlot);
  reach(body);
  if (marks_[body].crushed) return;  // reported once a step, from whichever side found it first
  marks_[body].crushed = true;
  ctx.crushes.push_back({body, anchor, blocker, static_cast<Axis>(axis)});
  ++ctx.stats.crush_events;
}

}  // namespace chain::detail
