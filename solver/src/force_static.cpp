// SPDX-License-Identifier: MIT
#include "force_static.h"

#include "buffer.h"

#include <algorithm>
#include <cmath>

namespace chain::detail {
namespace {

// The walls of the current chain along an axis, for StepContext::place.
struct WallsOf {
  const ChainState* state;
  int axis;
  static bool passes(const void* arg, std::uint32_t c) {
    const auto* w = static_cast<const WallsOf*>(arg);
    return w->state->walled(c, w->axis);
  }
};

}  // namespace

void ForceStatic::run(StepContext& ctx, ChainState& state) {
  const double tol = ctx.def.touch_tolerance;
  if (against_.size() < ctx.bodies.size()) resize_buffer(against_, ctx.bodies.size());
  for (const Item& root : queue_) {
    state.wall(root.body, root.axis);
    against_[root.body] = root.wall;
  }
  // Kept in a register: written through ctx, it would be reloaded after every store of the loop.
  std::uint32_t max_depth = ctx.stats.max_depth;
  const OverlapTest test(tol);  // made once for every wall's walk
  // The queue's length, counted here: queue_.size() divides by the 20-byte item at every wall.
  std::size_t queued = queue_.size();
  for (std::size_t k = 0; k < queued && !state.cut; ++k) {
    const Item item = queue_[k];
    const std::uint32_t w = item.body;
    if (rows_ && state.crushed(w)) continue;  // placed with its crushed row: nothing to push
    const int axis = item.axis;
    auto p = [&](std::uint32_t i) { return ctx.bodies.pos(axis, i); };
    auto h = [&](std::uint32_t i) { return ctx.bodies.half(axis, i); };
    max_depth = std::max(max_depth, item.depth);
    cands_.clear();
    // Only an immovable body other than its wall can squeeze w: most walls meet none, and skip
    // the call.
    if (state.gather_overlaps(ctx, w, cands_, test)) {
      for (const std::uint32_t d : cands_) {
        if (d != item.wall && ctx.bodies.immovable(d)) {
          crush_check(ctx, state, item);
          break;
        }
      }
    }
    for (std::size_t i = 0; i < cands_.size(); ++i) {
      const std::uint32_t c = cands_[i];
      if (ctx.bodies.immovable(c) || state.crushed(c)) continue;
      const Overlap o = overlap(ctx.bodies, w, c);
      if (o.x <= tol || o.y <= tol) continue;  // a yield may have moved w off it
      if (state.visited(c) && !state.walled(c, axis)) {
        // Bodies held by open frames follow back when their frame closes; any other body already
        // in this chain keeps its overlap for the next pass.
        if (state.on_stack(c) == 0) state.flag(w, c);
        continue;
      }
      if (overlap_axis(o) != axis) {
        state.flag(w, c);  // they meet across the chaining axis: the next pass takes it
        continue;
      }
      // The side c started the step on: a wall lands where its own wall puts it, which may be on
      // or past c's middle, and c is still pushed on the side it was on.
      const int dir = ChainState::side_at_start(ctx, axis, w, c);
      if (dir == item.backing) [[unlikely]] {
        const Between next = between(ctx, state, w, c, axis, axis == 0 ? o.x : o.y);
        if (next == Between::kStop) break;
        if (next == Between::kAgain) i = static_cast<std::size_t>(-1);
        continue;
      }
      if (state.supported_towards(axis, c, dir)) [[unlikely]] {
        // Supported beyond the wall while the wall is supported behind: a squeeze.
        if (squeeze(ctx, state, item, c, dir)) break;
        continue;
      }
      if (!state.spend(ctx, c)) break;
      // A wall the chain placed already, met by another wall of the chain on that wall's free
      // side, rests on the higher of the two: it moves on and its own walls follow (it is
      // queued again). Each such move is further the same way, so this ends.
      ctx.note_push(c, w, axis, dir);
      // Placed against w rather than moved by the depth: resting stacks rebuild the same
      // positions every step instead of accumulating rounding.
      // Guarded (StepContext::move) against every body but the walls of this chain: c may land
      // on or past the middle of another wall of it, which is pushed on the side it started on
      // all the same (side_at_start), and where two walls of the chain meet the squeeze is found;
      // but it never jumps past a body the chain has not placed.
      const double flush = p(w) + dir * (h(c) + h(w) - kept_squeeze(ctx, c, w, axis));
      const WallsOf walls{&state, axis};
      ctx.place(c, axis, flush, kNoSlot, true, &WallsOf::passes, &walls);
      if (p(c) != flush) [[unlikely]] {
        // Stopped short: not flush, so not a wall this chain can build on; the next pass
        // resolves what is left.
        state.visit(c);
        state.flag(w, c);
        continue;
      }
      state.wall_supported(c, axis, -dir, item.anchor);
      against_[c] = w;
      queue_.push_back(
          {c, w, item.depth + 1, item.anchor, item.axis, static_cast<std::int8_t>(-dir)});
      ++queued;
    }
  }
  ctx.stats.max_depth = max_depth;
  queue_.clear();
}

// Kept out of run(): rare, and inlined there it took registers from the common path.
[[gnu::noinline]] ForceStatic::Between ForceStatic::between(StepContext& ctx, ChainState& state,
                                                            std::uint32_t w, std::uint32_t c,
                                                            int axis, double depth) {
  // c lies between the wall and the wall's own support. If c rests on that side too, the wall
  // rests on c; otherwise c is not this wall's to push.
  const int dir = ChainState::side_at_start(ctx, axis, w, c);
  if (!state.supported_towards(axis, c, dir)) {
    state.flag(w, c);
    return Between::kNext;
  }
  // The overlap a squeezed row keeps between its bodies is contact: nothing to yield.
  if (squeezes_ && depth <= kept_squeeze(ctx, w, c, axis) + ctx.def.touch_tolerance) {
    return Between::kNext;
  }
  if (!state.spend(ctx, c)) return Between::kStop;
  if (!yield(ctx, state, w, c, axis)) {
    state.flag(w, c);  // a body beyond w keeps it from yielding: the next pass takes it
    return Between::kNext;
  }
  cands_.clear();  // w moved: look again from its new place
  state.gather_overlaps(ctx, w, cands_);
  return Between::kAgain;
}

bool ForceStatic::yield(StepContext& ctx, ChainState& state, std::uint32_t w, std::uint32_t c,
                        int axis) {
  const int c_side = ChainState::side_at_start(ctx, axis, w, c);
  auto p = [&](std::uint32_t i) { return ctx.bodies.pos(axis, i); };
  auto h = [&](std::uint32_t i) { return ctx.bodies.half(axis, i); };
  ctx.note_push(w, c, axis, -c_side);
  const double target = p(c) - c_side * (h(w) + h(c));
  const WallsOf walls{&state, axis};  // guarded as a placement is (run())
  ctx.place(w, axis, target, kNoSlot, true, &WallsOf::passes, &walls);
  state.flag(w);  // bodies this wall already pushed may now overlap it again
  return p(w) == target;
}

// item.body was pushed against item.wall, away from its backing; an immovable body overlapping
// it beyond, along the chaining axis, squeezes it: it is centred between the two and reported.
// Kept out of run(): called only for the walls that meet an immovable body besides their own.
[[gnu::noinline]] void ForceStatic::crush_check(StepContext& ctx, ChainState& state,
                                                const Item& item) {
  const Bodies& bodies = ctx.bodies;
  const double tol = ctx.def.touch_tolerance;
  const int axis = item.axis;
  auto p = [&](std::uint32_t i) { return bodies.pos(axis, i); };
  auto h = [&](std::uint32_t i) { return bodies.half(axis, i); };
  const std::uint32_t body = item.body, wall = item.wall;
  const int side = -item.backing;
  for (const std::uint32_t d : cands_) {
    if (d == wall || !bodies.immovable(d)) continue;
    const Overlap o = overlap(bodies, body, d);
    if (o.x <= tol || o.y <= tol || overlap_axis(o) != axis) continue;
    if ((p(d) - p(wall)) * side <= 0.0) continue;  // d is on the wall's side, not beyond body
    // The row from the anchor through body takes the squeeze together, when the walls lead back
    // to an immovable body.
    row_.clear();
    const std::uint32_t anchor = walls_back(ctx, state, body, axis, row_);
    std::reverse(row_.begin(), row_.end());
    if (anchor != kNoSlot && anchor != d && squeeze_row(ctx, state, anchor, d, axis)) return;
    const double wall_face = p(wall) + side * h(wall);
    const double blocker_face = p(d) - side * h(d);
    ctx.place(body, axis, 0.5 * (wall_face + blocker_face));
    ctx.note_push(body, d, axis, -side);
    state.report_crush(ctx, body, item.anchor == kNoSlot ? wall : item.anchor, d, axis);
    return;
  }
}

void ForceStatic::begin_step(std::size_t bodies) {
  if (squeezed_.size() != bodies) assign_buffer(squeezed_, bodies, 0);
  if (++step_ == 0xffffffffu) forget_slots();
  squeezes_ = squeezes_ > 0 ? squeezes_ - 1 : 0;  // counts down from 2: this step and the next
  rows_ = 0;
}

void ForceStatic::mark() {
  marked_ = {step_, squeezes_, rows_, true};
  undo_.clear();
}

void ForceStatic::undo() {
  for (auto k = undo_.size(); k-- > 0;)
    squeezed_[undo_[k].first] = undo_[k].second;
  undo_.clear();
  step_ = marked_.step;
  squeezes_ = marked_.squeezes;
  rows_ = marked_.rows;
  marked_.on = false;
}

void ForceStatic::forget_slots() {
  std::fill(squeezed_.begin(), squeezed_.end(), 0u);
  step_ = 1;
  squeezes_ = 0;
}

// Kept out of run(): its loop runs for every wall of every step, a squeeze seldom.
[[gnu::noinline]] bool ForceStatic::squeeze(StepContext& ctx, ChainState& state, const Item& item,
                                            std::uint32_t c, int dir) {
  const std::uint32_t w = item.body;
  const int axis = item.axis;
  // The row from the wall's anchor through w, and on through c to c's, takes it together. A body
  // between w and c as the step began, placed against w already or still to be placed by run()'s
  // loop, is the end of this side's row: the squeeze is found again from it.
  for (const std::uint32_t e : cands_) {
    if (e == c || ctx.bodies.immovable(e) || state.crushed(e)) continue;
    const bool placed_here = state.walled(e, axis) && against_[e] == w;
    if ((placed_here || !state.visited(e)) && ChainState::side_at_start(ctx, axis, w, e) == dir &&
        ChainState::side_at_start(ctx, axis, e, c) == dir) {
      return false;
    }
  }
  // The row goes on through the body of the other side nearest to w when the step began (w may
  // overlap several of them).
  std::uint32_t next = c;
  for (const std::uint32_t d : cands_) {
    if (d == w || ctx.bodies.immovable(d) || !state.walled(d, axis) ||
        !state.supported_towards(axis, d, dir) ||
        ChainState::side_at_start(ctx, axis, w, d) != dir) {
      continue;
    }
    if (std::abs(ctx.bodies.start_pos(axis, d) - ctx.bodies.start_pos(axis, w)) <
        std::abs(ctx.bodies.start_pos(axis, next) - ctx.bodies.start_pos(axis, w))) {
      next = d;
    }
  }
  row_.clear();
  const std::uint32_t anchor = walls_back(ctx, state, w, axis, row_);
  std::reverse(row_.begin(), row_.end());
  const std::uint32_t blocker = walls_back(ctx, state, next, axis, row_);
  if (anchor == kNoSlot || blocker == kNoSlot || !squeeze_row(ctx, state, anchor, blocker, axis)) {
    state.report_crush(ctx, w, item.anchor, state.support_anchor(c), axis);
  }
  return true;
}

std::uint32_t ForceStatic::walls_back(const StepContext& ctx, const ChainState& state,
                                      std::uint32_t from, int axis,
                                      std::vector<std::uint32_t>& out) const {
  std::uint32_t b = from;
  for (std::uint32_t steps = 0; steps <= ctx.bodies.dynamic_end; ++steps) {
    if (!state.walled(b, axis)) return kNoSlot;
    out.push_back(b);
    const std::uint32_t next = against_[b];
    if (next == kNoSlot) return kNoSlot;
    if (ctx.bodies.immovable(next)) return next;
    b = next;
  }
  return kNoSlot;
}

bool ForceStatic::squeeze_row(StepContext& ctx, ChainState& state, std::uint32_t anchor,
                              std::uint32_t blocker, int axis) {
  Bodies& bodies = ctx.bodies;
  if (anchor == blocker || row_.empty()) return false;
  auto p = [&](std::uint32_t i) { return bodies.pos(axis, i); };
  auto h = [&](std::uint32_t i) { return bodies.half(axis, i); };
  const double side = p(blocker) > p(anchor) ? 1.0 : -1.0;
  const double from = p(anchor) + side * h(anchor), to = p(blocker) - side * h(blocker);
  double length = 0.0;
  for (std::size_t k = 0; k < row_.size(); ++k) {
    length += 2.0 * h(row_[k]);
    // A row, in order from the anchor to the blocker (as the step found them: the walls may have
    // landed on each other's middles since), each body a wall of this chain.
    if (k > 0 &&
        side * (bodies.start_pos(axis, row_[k]) - bodies.start_pos(axis, row_[k - 1])) <= 0.0)
      return false;
  }
  // Every one of the row's contacts, the two faces' included, overlaps by the same depth.
  const double depth = (length - side * (to - from)) / static_cast<double>(row_.size() + 1);
  double at = from - side * depth;  // the near face of the next body
  for (std::size_t k = 0; k < row_.size(); ++k) {
    const std::uint32_t b = row_[k];
    // Each pressed against the one before it: the velocity rule takes the row as one group,
    // held by both immovable bodies.
    ctx.note_push(b, k == 0 ? anchor : row_[k - 1], axis, side);
    ctx.set(b, axis, at + side * h(b));
    at += side * (2.0 * h(b) - depth);
    state.report_crush(ctx, b, anchor, blocker, axis);
    state.flag(b);  // what rests on the row may overlap it now
    // A lone body is centred between the two faces again from scratch every step; a row keeps
    // its squeeze, so that the step adds only what it closes (kept_squeeze).
    if (row_.size() > 1) {
      if (marked_.on) undo_.push_back({b, squeezed_[b]});
      squeezed_[b] = step_;
    }
  }
  ctx.note_push(row_.back(), blocker, axis, -side);  // held by the blocker too (velocity rule)
  if (row_.size() > 1) squeezes_ = 2;
  ++rows_;
  return true;
}

}  // namespace chain::detail
