#include "force_static.h"

#include <algorithm>

namespace chain::detail {
void ForceStatic::run(StepContext& ctx, ChainState& state) {
  const double tol = ctx.def.touch_tolerance;
  for (const Item& root : queue_)
    state.wall(root.body, root.axis);
  for (std::size_t k = 0; k < queue_.size() && !state.cut; ++k) {
    const Item item = queue_[k];
    const std::uint32_t w = item.body;
    const int axis = item.axis;
    auto p = [&](std::uint32_t i) { return ctx.bodies.pos(axis, i); };
    auto h = [&](std::uint32_t i) { return ctx.bodies.half(axis, i); };
    ctx.stats.max_depth = std::max(ctx.stats.max_depth, item.depth);
    cands_.clear();
    state.gather_overlaps(ctx, w, cands_);
    crush_check(ctx, state, item);
    for (std::size_t i = 0; i < cands_.size(); ++i) {
      const std::uint32_t c = cands_[i];
      if (ctx.bodies.immovable(c) || state.crushed(c)) continue;
      const Overlap o = overlap(ctx.bodies, w, c);
      if (o.x <= tol || o.y <= tol) continue;  // a yield may have moved w off it
      if (state.visited(c) && !state.walled(c, axis)) {
        // Bodies held by open frames follow back when their frame closes; any other body already
        // in this chain keeps its overlap for the next sweep.
        if (state.on_stack(c) == 0) state.flag(w, c);
        continue;
      }
      if (overlap_axis(o) != axis) {
        state.flag(w, c);  // they meet across the chaining axis: the next sweep takes it
        continue;
      }
      const int dir = ChainState::away(ctx, axis, w, c);
      if (dir == item.backing) {
        // c lies between the wall and the wall's own support. If c rests on that side too, the
        // wall rests on c; otherwise c is not this wall's to push.
        if (!state.supported_towards(axis, c, dir)) {
          state.flag(w, c);
          continue;
        }
        if (!state.spend(ctx)) break;
        if (!yield(ctx, state, w, c, axis)) {
          state.flag(w, c);  // a body beyond w keeps it from yielding: the next sweep takes it
          continue;
        }
        cands_.clear();  // w moved: look again from its new place
        state.gather_overlaps(ctx, w, cands_);
        i = static_cast<std::size_t>(-1);
        continue;
      }
      if (state.supported_towards(axis, c, dir)) {
        // Supported beyond the wall while the wall is supported behind: a squeeze.
        state.report_crush(ctx, w, item.anchor, state.support_anchor(c), axis);
        break;
      }
      if (!state.spend(ctx)) break;
      // A wall the chain placed already, met by another wall of the chain on that wall's free
      // side, rests on the higher of the two: it moves on and its own walls follow (it is
      // queued again). Each such move is further the same way, so this ends.
      ctx.note_push(c, w, axis, dir);
      // Placed against w rather than moved by the depth: resting stacks rebuild the same
      // positions every step instead of accumulating rounding.
      const double flush = p(w) + dir * (h(c) + h(w));
      ctx.place(c, axis, flush);
      if (p(c) != flush) {
        // Stopped short by a body in its way (StepContext::move): not flush, so not a wall this
        // chain can build on; the next sweep resolves what is left.
        state.visit(c);
        state.flag(w, c);
        continue;
      }
      state.wall(c, axis);
      state.support(axis, c, -dir, item.anchor);
      queue_.push_back(
          {c, w, item.depth + 1, item.anchor, item.axis, static_cast<std::int8_t>(-dir)});
    }
  }
  queue_.clear();
}

bool ForceStatic::yield(StepContext& ctx, ChainState& state, std::uint32_t w, std::uint32_t c,
                        int axis) {
  const int c_side = ChainState::away(ctx, axis, w, c);
  auto p = [&](std::uint32_t i) { return ctx.bodies.pos(axis, i); };
  auto h = [&](std::uint32_t i) { return ctx.bodies.half(axis, i); };
  ctx.note_push(w, c, axis, -c_side);
  const double target = p(c) - c_side * (h(w) + h(c));
  ctx.place(w, axis, target);
  state.flag(w);  // bodies this wall already pushed may now overlap it again
  return p(w) == target;
}

// item.body was pushed against item.wall, away from its backing; an immovable body overlapping
// it beyond, along the chaining axis, squeezes it: it is centred between the two and reported.
void ForceStatic::crush_check(StepContext& ctx, ChainState& state, const Item& item) {
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
    const double wall_face = p(wall) + side * h(wall);
    const double blocker_face = p(d) - side * h(d);
    ctx.place(body, axis, 0.5 * (wall_face + blocker_face));
    ctx.note_push(body, d, axis, -side);
    state.report_crush(ctx, body, item.anchor == kNoSlot ? wall : item.anchor, d, axis);
    return;
  }
}

}  // namespace chain::detail
