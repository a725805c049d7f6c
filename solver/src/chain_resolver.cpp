#include "chain_resolver.h"

#include <algorithm>
#include <cmath>

namespace chain::detail {
namespace {

constexpr std::uint32_t kUnreached = 0xffffffffu;

}  // namespace

void ChainResolver::resolve(StepContext& ctx) {
  Bodies& bodies = ctx.bodies;
  const double tol = ctx.def.touch_tolerance;
  if (level_.capacity() < bodies.size()) {
    // The body set grew: size the per-body buffers for it now, not in some later step.
    const std::size_t n = bodies.size();
    for (auto* v : {&level_, &adj_start_, &queue_, &level_count_})
      v->reserve(n + 3);
    contacts_.reserve(2 * n), ordered_.reserve(2 * n), adj_.reserve(4 * n),
        near_pairs_.reserve(4 * n);
  }
  state_.begin_step(ctx);
  state_.leftover = true;
  for (int pass = 0; pass < ctx.def.max_passes && state_.leftover; ++pass) {
    state_.leftover = false;
    if (pass == 0) {
      gather_contacts(ctx);
    } else {
      gather_suspect_contacts(ctx);
    }
    state_.clear_suspects();
    ++ctx.stats.passes;
    ctx.stats.contacts += static_cast<std::uint32_t>(contacts_.size());
    if (contacts_.empty()) break;
    order_contacts(ctx);
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
  }
}

void ChainResolver::forget_slots() {
  state_.forget_slots();
  std::fill(local_mark_.begin(), local_mark_.end(), 0u);
  mark_ = 0;
  near_generation_ = 0;
}

// A grid scan gives the near pairs (closer than the slack), which chains look through instead of
// the grid while bodies have moved less than half the slack. While no body has moved a quarter
// of the slack since that scan, they still hold every pair that can overlap, and no new scan is
// needed: the contacts (overlapping pairs) are always found among them.
void ChainResolver::gather_contacts(StepContext& ctx) {
  const Bodies& bodies = ctx.bodies;
  const double tol = ctx.def.touch_tolerance;
  if (near_generation_ == ctx.broadphase.generation() && ctx.broadphase.near_pairs_hold()) {
    state_.begin_sweep(bodies, nullptr);
  } else {
    ctx.broadphase.build(bodies);
    near_generation_ = ctx.broadphase.generation();
    near_pairs_.clear();
    ctx.broadphase.for_each_near_pair([&](std::uint32_t i, std::uint32_t j) {
      near_pairs_.push_back({i, j});
    });
    state_.begin_sweep(bodies, &near_pairs_);
  }
  // Walked body by body in solve order, each pair taken at its later body: the earlier one was
  // just read and is still in cache, and the contacts come out in an order that depends on the
  // bodies alone.
  contacts_.clear();
  for (std::uint32_t i = 0; i < bodies.size(); ++i) {
    const double x = bodies.x(i), y = bodies.y(i), hx = bodies.hx(i), hy = bodies.hy(i);
    for (const std::uint32_t j : state_.near(i)) {
      if (j < i && (hx + bodies.hx(j)) - std::abs(x - bodies.x(j)) > tol &&
          (hy + bodies.hy(j)) - std::abs(y - bodies.y(j)) > tol) {
        contacts_.push_back({j, i});
      }
    }
  }
}

// A later sweep can only find the overlaps the last one's chains left behind, and those flagged
// the bodies involved: the contacts are among the near pairs of those bodies, while they hold.
void ChainResolver::gather_suspect_contacts(StepContext& ctx) {
  const Broadphase& bp = ctx.broadphase;
  if (near_generation_ != bp.generation() || !bp.near_pairs_hold()) {
    near_generation_ = 0;  // forces a new scan
    gather_contacts(ctx);
    return;
  }
  const Bodies& bodies = ctx.bodies;
  const double tol = ctx.def.touch_tolerance;
  contacts_.clear();
  for (const std::uint32_t i : state_.suspects()) {
    for (const std::uint32_t j : state_.near(i)) {
      if (state_.suspect(j) && j < i) continue;  // both flagged: the pair is taken once
      const Overlap o = overlap(bodies, i, j);
      if (o.x > tol && o.y > tol) contacts_.push_back({std::min(i, j), std::max(i, j)});
    }
  }
  state_.begin_sweep(bodies, nullptr);
}

// Levels: immovable bodies 0, dynamic bodies their contact-graph distance from one (breadth
// first), unreached last. Contacts are stably sorted by the lower level of their two bodies, and
// a dynamic pair is oriented so that `a` is the body nearer to the immovable ones.
void ChainResolver::order_contacts(StepContext& ctx) {
  const Bodies& bodies = ctx.bodies;
  // Number the dynamic bodies the contacts touch: the work is in proportion to the contacts, not
  // to the world.
  if (local_.size() != bodies.size()) {
    local_.assign(bodies.size(), 0);
    local_mark_.assign(bodies.size(), 0);
    mark_ = 0;
  }
  if (++mark_ == 0) {
    std::fill(local_mark_.begin(), local_mark_.end(), 0u);
    mark_ = 1;
  }
  involved_.clear();
  auto local = [&](std::uint32_t body) {
    if (local_mark_[body] != mark_) {
      local_mark_[body] = mark_;
      local_[body] = static_cast<std::uint32_t>(involved_.size());
      involved_.push_back(body);
    }
    return local_[body];
  };
  for (const Pair& c : contacts_) {
    local(c.a);  // c.a < c.b and dynamic slots come first: c.a is dynamic
    if (!bodies.immovable(c.b)) local(c.b);
  }
  const auto m = static_cast<std::uint32_t>(involved_.size());
  level_.assign(m, kUnreached);
  adj_start_.assign(m + 2, 0);
  queue_.clear();
  for (const Pair& c : contacts_) {
    const std::uint32_t a = local_[c.a];
    if (bodies.immovable(c.b)) {
      if (level_[a] == kUnreached) {
        level_[a] = 1;
        queue_.push_back(a);
      }
    } else {
      ++adj_start_[a + 2];
      ++adj_start_[local_[c.b] + 2];
    }
  }
  for (std::uint32_t i = 2; i < m + 2; ++i)
    adj_start_[i] += adj_start_[i - 1];
  adj_.resize(adj_start_[m + 1]);
  for (const Pair& c : contacts_) {  // adj_start_[i + 1] is the fill cursor of local body i
    if (bodies.immovable(c.b)) continue;
    const std::uint32_t a = local_[c.a], b = local_[c.b];
    adj_[adj_start_[a + 1]++] = b;
    adj_[adj_start_[b + 1]++] = a;
  }
  for (std::size_t k = 0; k < queue_.size(); ++k) {
    const std::uint32_t u = queue_[k];
    for (std::uint32_t e = adj_start_[u]; e < adj_start_[u + 1]; ++e) {
      const std::uint32_t v = adj_[e];
      if (level_[v] != kUnreached) continue;
      level_[v] = level_[u] + 1;
      queue_.push_back(v);
    }
  }

  std::uint32_t top = 0;
  for (const std::uint32_t u : queue_)
    top = std::max(top, level_[u]);
  const std::uint32_t last = top + 1;  // the bucket of contacts no immovable body reaches
  auto bucket = [&](const Pair& c) {
    return bodies.immovable(c.b) ? 0u : std::min({level_[local_[c.a]], level_[local_[c.b]], last});
  };
  level_count_.assign(last + 2, 0);
  for (const Pair& c : contacts_)
    ++level_count_[bucket(c) + 1];
  for (std::size_t l = 1; l < level_count_.size(); ++l)
    level_count_[l] += level_count_[l - 1];
  ordered_.resize(contacts_.size());
  for (const Pair& c : contacts_) {
    Pair o = c;
    if (!bodies.immovable(c.b) && level_[local_[c.b]] < level_[local_[c.a]]) std::swap(o.a, o.b);
    ordered_[level_count_[bucket(c)]++] = o;
  }
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
        if (!open(ctx, f.a, c, f.extra + bodies.mass[f.b], f.chain_axis, w, w ? c : kNoSlot)) {
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
      if (!open(ctx, f.b, c, f.extra + bodies.mass[f.a], f.chain_axis, w, w ? c : kNoSlot)) {
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
                         bool force_static, std::uint32_t anchor) {
  Frame& f = last_;
  f = Frame{};
  f.a = a;
  f.b = b;
  f.anchor = anchor;
  if (!state_.spend(ctx)) return false;
  Bodies& bodies = ctx.bodies;
  state_.visit(a);
  if (!bodies.immovable(b)) state_.visit(b);
  const auto depth = static_cast<std::uint32_t>(stack_.size() + 1);
  ctx.stats.max_depth = std::max(ctx.stats.max_depth, depth);

  const double tol = ctx.def.touch_tolerance;
  const Overlap o = overlap(bodies, a, b);
  if (o.x <= tol || o.y <= tol) return false;
  const int push_axis = overlap_axis(o);
  if (axis != kAnyAxis && push_axis != axis) {
    state_.flag(a, b);  // an overlap across the chaining axis: the next sweep takes it
    return false;
  }
  const int sign = ChainState::away(ctx, push_axis, b, a);
  f.chain_axis = static_cast<std::int8_t>(push_axis);
  f.sign = static_cast<std::int8_t>(sign);
  if (!force_static && state_.supported_towards(push_axis, b, -sign)) {
    force_static = true;  // b would be pushed into its own support: it is a wall here
    f.anchor = anchor = state_.support_anchor(b);
  }
  ctx.note_push(a, b, push_axis, sign);

  auto p = [&](std::uint32_t i) { return ctx.bodies.pos(push_axis, i); };
  auto h = [&](std::uint32_t i) { return ctx.bodies.half(push_axis, i); };
  if (force_static) {
    // Placed against b rather than moved by the depth: resting stacks rebuild the same
    // positions every step instead of accumulating rounding.
    f.moved = ctx.place(a, push_axis, p(b) + sign * (h(a) + h(b)));
    f.backing = static_cast<std::int8_t>(-sign);
    state_.support(push_axis, a, -sign, anchor);
    walls_.add({a, b, push_axis, -sign, anchor, depth});  // the caller runs the walls
    return false;
  }
  const double depth_along = sign * (push_axis == 0 ? o.x : o.y);
  const double mass_a = bodies.mass[a] + extra;
  const double mass_b = bodies.mass[b];
  f.moved = depth_along * (mass_b / (mass_a + mass_b));
  ctx.move(a, push_axis, f.moved);
  ctx.move(b, push_axis, f.moved - depth_along);
  f.extra = extra;
  f.axis = static_cast<std::int8_t>(axis);
  f.stage = Stage::kBack;
  f.cand_begin = f.cand_end = f.cursor = static_cast<std::uint32_t>(cands_.size());
  ++state_.on_stack(a);
  ++state_.on_stack(b);
  stack_.push_back(f);
  gather_candidates(ctx, stack_.back(), a);
  return true;
}

void ChainResolver::gather_candidates(StepContext& ctx, Frame& f, std::uint32_t around) {
  cands_.resize(f.cand_begin);
  state_.gather_overlaps(ctx, around, cands_);
  f.cand_end = static_cast<std::uint32_t>(cands_.size());
  f.cursor = f.cand_begin;
}

bool ChainResolver::next_candidate(StepContext& ctx, Frame& f, std::uint32_t from,
                                   std::uint32_t& c) {
  const Bodies& bodies = ctx.bodies;
  const double tol = ctx.def.touch_tolerance;
  while (f.cursor < f.cand_end) {
    c = cands_[f.cursor++];
    if (c == f.a || c == f.b) continue;
    const bool immovable = bodies.immovable(c);
    if (!immovable && state_.crushed(c)) continue;
    const Overlap o = overlap(bodies, from, c);
    if (o.x <= tol || o.y <= tol) continue;
    if (!immovable && state_.visited(c)) {
      // Bodies still on the stack follow back when their frame closes; any other body already
      // in this chain keeps its overlap for the next sweep.
      if (state_.on_stack(c) == 0) state_.flag(from, c);
      continue;
    }
    return true;
  }
  return false;
}

void ChainResolver::close(StepContext& ctx) {
  const Frame done = stack_.back();
  stack_.pop_back();
  cands_.resize(done.cand_begin);
  --state_.on_stack(done.a);
  --state_.on_stack(done.b);
  if (!stack_.empty()) hand_back(ctx, done);
}

void ChainResolver::hand_back(StepContext& ctx, const Frame& done) {
  Frame& p = stack_.back();
  if (p.stage == Stage::kBack) {  // done.a == p.a: b follows a
    if (done.moved != 0.0) {
      ctx.move(p.b, p.chain_axis, done.moved);
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
    ctx.move(p.a, p.chain_axis, done.moved);
    p.moved += done.moved;
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
