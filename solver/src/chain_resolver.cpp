// SPDX-License-Identifier: MIT
#include "chain_resolver.h"

#include "buffer.h"

#include "entry_face.h"

#include <algorithm>
#include <cmath>

namespace chain::detail {

void ChainResolver::resolve(StepContext& ctx) {
  Bodies& bodies = ctx.bodies;
  const double tol = ctx.def.touch_tolerance;
  if (level_.capacity() < bodies.size()) {
    // The body set grew: size the per-body buffers for it now, not in some later step.
    const std::size_t n = bodies.size();
    for (auto* v : {&level_, &adj_start_, &queue_, &level_count_})
      reserve_buffer(*v, n + 3);
    // The contact lists (contacts_, ordered_, adj_) are sized by the steps that fill them.
  }
  state_.begin_step(ctx);
  walls_.begin_step(bodies.size());
  test_ = OverlapTest(tol);
  ctx.clock.lap(ctx.profile.prepare);
  fresh_grid_ = continuous_.run(ctx, state_);
  ctx.clock.lap(ctx.profile.continuous);
  state_.leftover = true;
  for (int pass = 0; pass < ctx.def.max_passes && state_.leftover; ++pass) {
    state_.leftover = false;
    if (pass == 0) {
      gather_contacts(ctx);
    } else {
      gather_suspect_contacts(ctx);
    }
    state_.clear_suspects();
    if (ctx.skipped != nullptr) {
      // Bodies the step leaves out resolve nothing; a pair with one of them is a meeting the
      // step's check finds (islands.h), and the step is solved again whole.
      std::erase_if(contacts_, [&](const Pair& p) { return ctx.skipped[p.a] || ctx.skipped[p.b]; });
    }
    ++ctx.stats.passes;
    ctx.stats.contacts += static_cast<std::uint32_t>(contacts_.size());
    if (contacts_.empty()) {
      ctx.clock.lap(ctx.profile.contacts);
      break;
    }
    order_contacts(ctx);
    if (repeat_immovable_) {
      std::size_t count = 0;
      while (count < ordered_.size() && bodies.immovable(ordered_[count].b))
        ++count;
      order_entries(ctx, count);
    }
    ctx.clock.lap(ctx.profile.contacts);
    // Contacts with immovable bodies come first: every dynamic body there is placed against its
    // immovable body, and the walls they become propagate together, one chain, layer by layer.
    std::size_t k = 0;
    state_.begin_chain();
    for (; k < ordered_.size() && bodies.immovable(ordered_[k].b); ++k) {
      const Pair& c = ordered_[k];
      if (state_.crushed(c.a) || !overlapping(bodies, c.a, c.b, tol)) continue;
      if (ctx.budget == 0) {
        ++ctx.stats.budget_hits;  // a contact no chain could reach
        continue;
      }
      open(ctx, c.a, c.b, 0.0, kAnyAxis, true, c.b);
    }
    walls_.run(ctx, state_);
    if (state_.cut) ++ctx.stats.budget_hits;
    for (; k < ordered_.size(); ++k) {
      const Pair& c = ordered_[k];
      if (state_.crushed(c.a) || state_.crushed(c.b) || !overlapping(bodies, c.a, c.b, tol))
        continue;
      if (ctx.budget == 0) {
        ++ctx.stats.budget_hits;
        continue;
      }
      run_chain(ctx, c.a, c.b);
    }
    ctx.clock.lap(ctx.profile.chains);
  }
}

void ChainResolver::forget_slots() {
  state_.forget_slots();
  walls_.forget_slots();
  std::fill(local_mark_.begin(), local_mark_.end(), 0u);
  mark_ = 0;
  near_generation_ = kNotScanned;
}

bool ChainResolver::next_candidate(StepContext& ctx, Frame& f, std::uint32_t from,
                                   std::uint32_t& c) {
  const Bodies& bodies = ctx.bodies;
  const double tol = ctx.def.touch_tolerance;
  while (f.cursor < f.cand_end) {
    c = cands_[f.cursor++];
    if (c == f.a || c == f.b) continue;
    // The overlap first: most candidates fail it, and it reads no per-body marks.
    const Overlap o = overlap(bodies, from, c);
    if (o.x <= tol || o.y <= tol) continue;
    const bool immovable = bodies.immovable(c);
    if (!immovable && state_.crushed(c)) continue;
    if (!immovable && state_.visited(c)) {
      // Bodies still on the stack follow back when their frame closes; any other body already
      // in this chain keeps its overlap for the next pass.
      if (state_.on_stack(c) == 0) state_.flag(from, c);
      continue;
    }
    return true;
  }
  return false;
}

void ChainResolver::run_chain(StepContext& ctx, std::uint32_t a, std::uint32_t b) {
  state_.begin_chain();
  cands_.clear();
  const bool wall = ctx.bodies.immovable(b);
  if (!wall) {
    // The body that is supported where it would be pushed is the one that stays.
    const int axis = overlap_axis(overlap(ctx.bodies, a, b));
    const int a_goes = ChainState::away(ctx, axis, b, a);
    if (state_.supported_towards(axis, a, a_goes) && !state_.supported_towards(axis, b, -a_goes)) {
      std::swap(a, b);
    }
  }
  if (!open(ctx, a, b, 0.0, kAnyAxis, wall, wall ? b : kNoSlot)) walls_.run(ctx, state_);
  while (!stack_.empty()) {
    Frame& f = stack_.back();
    std::uint32_t c = 0;
    const Bodies& bodies = ctx.bodies;
    if (f.stage == Stage::kBack) {  // a, pushed back, meets the bodies now in its way
      if (next_candidate(ctx, f, f.a, c)) {
        const bool w = bodies.immovable(c);
        if (!open(ctx, f.a, c, f.extra + bodies.mass[f.b], f.chain_axis, w, w ? c : kNoSlot, f.b)) {
          walls_.run(ctx, state_);
          hand_back(ctx, last_);
        }
      } else if (f.frozen) {  // a leans on an immovable body, and b on a: b is a wall now
        walls_.add(
            {f.b, f.a, f.chain_axis, f.sign, f.anchor, static_cast<std::uint32_t>(stack_.size())});
        walls_.run(ctx, state_);
        close(ctx);
      } else {
        f.stage = Stage::kForward;
        gather_candidates(ctx, f, f.b);
      }
    } else if (next_candidate(ctx, f, f.b, c)) {  // b carries the chain on, a's mass behind it
      const bool w = bodies.immovable(c);
      if (!open(ctx, f.b, c, f.extra + bodies.mass[f.a], f.chain_axis, w, w ? c : kNoSlot, f.a)) {
        walls_.run(ctx, state_);
        hand_back(ctx, last_);
      }
    } else {
      close(ctx);
    }
  }
  if (state_.cut) ++ctx.stats.budget_hits;
}

bool ChainResolver::open(StepContext& ctx, std::uint32_t a, std::uint32_t b, double extra, int axis,
                         bool force_static, std::uint32_t anchor, std::uint32_t follower) {
  last_ = Result{0.0, anchor, 0};
  if (!state_.spend(ctx, a)) return false;
  Bodies& bodies = ctx.bodies;
  state_.visit(a);
  if (!bodies.immovable(b)) state_.visit(b);
  const auto depth = static_cast<std::uint32_t>(stack_.size() + 1);
  ctx.stats.max_depth = std::max(ctx.stats.max_depth, depth);

  const double tol = ctx.def.touch_tolerance;
  const Overlap o = overlap(bodies, a, b);
  if (o.x <= tol || o.y <= tol) return false;
  int push_axis = overlap_axis(o);
  int sign = 0;
  if (bodies.immovable(b)) {
    const Face face = entry_face(ctx, a, b);  // out the way it came in, not the shortest way
    push_axis = face.axis;
    sign = face.sign;
  } else {
    sign = ChainState::away(ctx, push_axis, b, a);
  }
  if (axis != kAnyAxis && push_axis != axis) {
    state_.flag(a, b);  // an overlap across the chaining axis: the next pass takes it
    return false;
  }
  if (!force_static && state_.supported_towards(push_axis, b, -sign)) {
    force_static = true;  // b would be pushed into its own support: it is a wall here
    last_.anchor = anchor = state_.support_anchor(b);
  }
  ctx.note_push(a, b, push_axis, sign);

  auto p = [&](std::uint32_t i) { return ctx.bodies.pos(push_axis, i); };
  auto h = [&](std::uint32_t i) { return ctx.bodies.half(push_axis, i); };
  if (force_static) {
    // Placed against b rather than moved by the depth: resting stacks rebuild the same
    // positions every step instead of accumulating rounding.
    // A body of a row squeezed last step keeps the overlap it had (ForceStatic::kept_squeeze).
    const double target = p(b) + sign * (h(a) + h(b) - walls_.kept_squeeze(ctx, a, b, push_axis));
    last_.moved = ctx.place(a, push_axis, target, follower);
    if (p(a) != target) state_.flag(a, b);  // stopped short by a body in its way
    last_.backing = static_cast<std::int8_t>(-sign);
    state_.support(push_axis, a, -sign, anchor);
    walls_.add({a, b, push_axis, -sign, anchor, depth});  // the caller runs the walls
    return false;
  }
  const double depth_along = sign * (push_axis == 0 ? o.x : o.y);
  const double mass_a = bodies.mass[a] + extra;
  const double mass_b = bodies.mass[b];
  const double share = depth_along * (mass_b / (mass_a + mass_b));
  const double moved = ctx.move(a, push_axis, share, follower);
  // Either may stop short at a body in its way (StepContext::move): the rest of the overlap is
  // left to the chain that body starts, or to the next pass.
  if (ctx.move(b, push_axis, share - depth_along) != share - depth_along || moved != share)
    state_.flag(a, b);
  ++state_.on_stack(a);
  ++state_.on_stack(b);
  // Written in place, field by field: a frame built elsewhere and copied in was read back with
  // wide loads straight after its narrow stores, which stalled every open (store forwarding).
  Frame& f = stack_.emplace_back();
  f.a = a;
  f.b = b;
  f.anchor = anchor;
  f.cand_begin = f.cand_end = f.cursor = static_cast<std::uint32_t>(cands_.size());
  f.extra = extra;
  f.moved = moved;
  f.axis = static_cast<std::int8_t>(axis);
  f.chain_axis = static_cast<std::int8_t>(push_axis);
  f.sign = static_cast<std::int8_t>(sign);
  f.backing = 0;
  f.stage = Stage::kBack;
  f.frozen = false;
  gather_candidates(ctx, f, a);
  return true;
}

void ChainResolver::gather_candidates(StepContext& ctx, Frame& f, std::uint32_t around) {
  cands_.truncate(f.cand_begin);
  state_.gather_overlaps(ctx, around, cands_, test_);
  f.cand_end = static_cast<std::uint32_t>(cands_.size());
  f.cursor = f.cand_begin;
}

void ChainResolver::close(StepContext& ctx) {
  const Frame done = stack_.back();
  stack_.pop_back();
  cands_.truncate(done.cand_begin);
  --state_.on_stack(done.a);
  --state_.on_stack(done.b);
  if (!stack_.empty()) hand_back(ctx, {done.moved, done.anchor, done.backing});
}

void ChainResolver::hand_back(StepContext& ctx, const Result& done) {
  Frame& p = stack_.back();
  if (p.stage == Stage::kBack) {  // done.a == p.a: b follows a
    if (done.moved != 0.0) {
      if (ctx.move(p.b, p.chain_axis, done.moved) != done.moved) state_.flag(p.a, p.b);
      p.moved += done.moved;
      gather_candidates(ctx, p, p.a);  // a has moved: what it overlaps now, not before
    }
    if (done.backing != 0 && p.backing == 0) {
      p.backing = done.backing;
      p.anchor = done.anchor;
    }
    if (done.backing == p.sign && !p.frozen) {  // a is backed away from b, and b leans on a
      p.frozen = true;
      p.anchor = done.anchor;
      state_.support(p.chain_axis, p.b, p.sign, done.anchor);
    }
    return;
  }
  // done.a == p.b: a follows b
  if (done.moved != 0.0) {
    p.moved += ctx.move(p.a, p.chain_axis, done.moved);
    state_.flag(p.a);                // a has moved since its own neighbours were checked
    gather_candidates(ctx, p, p.b);  // and b: what it overlaps now, not before
  }
  if (done.backing == -p.sign) {  // b leans on an immovable body, and a on b
    p.backing = done.backing;
    p.anchor = done.anchor;
    state_.support(p.chain_axis, p.a, -p.sign, done.anchor);
  }
}

}  // namespace chain::detail
