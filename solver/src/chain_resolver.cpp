#include "chain_resolver.h"

#include <algorithm>
#include <cassert>

namespace chain::detail {
namespace {

constexpr std::uint32_t kUnreached = 0xffffffffu;

int overlap_axis(const Overlap& o) {
  return o.x <= o.y ? 0 : 1;
}  // ties go to x, as in 2014

}  // namespace

void ChainResolver::resolve(StepContext& ctx) {
  Bodies& bodies = ctx.bodies;
  const std::size_t n = bodies.size();
  const double tol = ctx.def.touch_tolerance;
  if (visited_.size() != n) {
    // The body set changed: size every per-body buffer for it now, not in some later step.
    for (auto* v : {&level_, &adj_start_, &queue_, &level_count_})
      v->reserve(n + 3);
    contacts_.reserve(2 * n), ordered_.reserve(2 * n), adj_.reserve(4 * n);
    ctx.crushes.reserve(std::min<std::size_t>(n, 1024));
  }
  visited_.resize(n, 0);
  on_stack_.assign(n, 0);
  crushed_.assign(n, 0);
  support_anchor_.resize(n);
  leftover_ = true;
  for (int pass = 0; pass < ctx.def.max_passes && leftover_; ++pass) {
    leftover_ = false;
    support_[0].assign(n, 0);  // supports hold within a sweep: bodies move between sweeps
    support_[1].assign(n, 0);
    ctx.broadphase.build(bodies);
    gather_contacts(ctx);
    ++ctx.stats.passes;
    ctx.stats.contacts += static_cast<std::uint32_t>(contacts_.size());
    if (contacts_.empty()) break;
    order_contacts(ctx);
    for (const Contact& c : ordered_) {
      if (crushed_[c.a] || crushed_[c.b]) continue;
      const Overlap o = overlap(bodies, c.a, c.b);
      if (o.x <= tol || o.y <= tol) continue;
      if (ctx.budget == 0) {
        ++ctx.stats.budget_hits;  // a contact no chain could reach
        continue;
      }
      run_chain(ctx, c.a, c.b);
    }
  }
}

void ChainResolver::gather_contacts(StepContext& ctx) {
  contacts_.clear();
  ctx.broadphase.for_each_overlapping_pair(ctx.bodies, ctx.def.touch_tolerance,
                                           [&](std::uint32_t i, std::uint32_t j) {
                                             contacts_.push_back({i, j});
                                           });
}

// Levels: immovable bodies 0, dynamic bodies their contact-graph distance from one (breadth
// first), unreached last. Contacts are stably sorted by the lower level of their two bodies, and
// a dynamic pair is oriented so that `a` is the body nearer to the immovable ones.
void ChainResolver::order_contacts(StepContext& ctx) {
  const Bodies& bodies = ctx.bodies;
  const std::uint32_t nd = bodies.dynamic_end;
  level_.assign(nd, kUnreached);
  adj_start_.assign(nd + 2, 0);
  queue_.clear();
  for (const Contact& c : contacts_) {
    if (bodies.immovable(c.b)) {  // c.a < c.b and dynamic slots come first: c.a is dynamic
      if (level_[c.a] == kUnreached) {
        level_[c.a] = 1;
        queue_.push_back(c.a);
      }
    } else {
      ++adj_start_[c.a + 2];
      ++adj_start_[c.b + 2];
    }
  }
  for (std::uint32_t i = 2; i < nd + 2; ++i)
    adj_start_[i] += adj_start_[i - 1];
  adj_.resize(adj_start_[nd + 1]);
  for (const Contact& c : contacts_) {  // adj_start_[i + 1] is the fill cursor of body i
    if (bodies.immovable(c.b)) continue;
    adj_[adj_start_[c.a + 1]++] = c.b;
    adj_[adj_start_[c.b + 1]++] = c.a;
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
  auto bucket = [&](const Contact& c) {
    return bodies.immovable(c.b) ? 0u : std::min({level_[c.a], level_[c.b], last});
  };
  level_count_.assign(last + 2, 0);
  for (const Contact& c : contacts_)
    ++level_count_[bucket(c) + 1];
  for (std::size_t l = 1; l < level_count_.size(); ++l)
    level_count_[l] += level_count_[l - 1];
  ordered_.resize(contacts_.size());
  for (const Contact& c : contacts_) {
    Contact o = c;
    if (!bodies.immovable(c.b) && level_[c.b] < level_[c.a]) std::swap(o.a, o.b);
    ordered_[level_count_[bucket(c)]++] = o;
  }
}

int ChainResolver::away(const StepContext& ctx, int axis, std::uint32_t from, std::uint32_t c) {
  const double* p = axis == 0 ? ctx.bodies.x.data() : ctx.bodies.y.data();
  return p[c] >= p[from] ? 1 : -1;
}

void ChainResolver::support(int axis, std::uint32_t body, int direction, std::uint32_t anchor) {
  support_[axis][body] = static_cast<std::int8_t>(direction);
  support_anchor_[body] = anchor;
}

void ChainResolver::run_chain(StepContext& ctx, std::uint32_t a, std::uint32_t b) {
  if (++stamp_ == 0) {  // wrapped: forget every old mark
    std::fill(visited_.begin(), visited_.end(), 0u);
    stamp_ = 1;
  }
  cut_ = false;
  cands_.clear();
  const bool wall = ctx.bodies.immovable(b);
  if (!wall) {
    // The body that is supported where it would be pushed is the one that stays.
    const int axis = overlap_axis(overlap(ctx.bodies, a, b));
    const int a_goes = away(ctx, axis, b, a);
    if (supported_towards(axis, a, a_goes) && !supported_towards(axis, b, -a_goes)) {
      std::swap(a, b);
    }
  }
  push_frame(ctx, a, b, 0.0, kAnyAxis, wall, wall ? b : kNoSlot);
  while (!stack_.empty()) {
    Frame& f = stack_.back();
    std::uint32_t c = 0;
    switch (f.stage) {
      case Stage::kEnter:
        if (!enter(ctx, f)) finish(ctx);
        break;
      case Stage::kWall:  // a acts as a wall for every dynamic body on its free side
        if (!next_candidate(ctx, f, f.a, c)) {
          finish(ctx);
          break;
        }
        if (const int dir = away(ctx, f.chain_axis, f.a, c); dir == f.backing) {
          // c lies between the wall and the wall's own support: if c rests on that side too,
          // the wall rests on c; otherwise c is not this wall's to push.
          if (supported_towards(f.chain_axis, c, dir)) {
            yield_to(ctx, f, c);
          } else {
            leftover_ = true;
          }
        } else if (supported_towards(f.chain_axis, c, dir)) {
          yield_to(ctx, f, c);  // backed on the far side: a squeeze
        } else {
          push_frame(ctx, c, f.a, 0.0, f.chain_axis, true, f.anchor);
        }
        break;
      case Stage::kBack:  // a, pushed back, meets the bodies now in its way
        if (next_candidate(ctx, f, f.a, c)) {
          const bool w = ctx.bodies.immovable(c);
          push_frame(ctx, f.a, c, f.extra + ctx.bodies.mass[f.b], f.chain_axis, w, w ? c : kNoSlot);
        } else {
          f.stage = Stage::kForward;
          gather_candidates(ctx, f, f.b);
          if (f.frozen) crush_check(ctx, f, f.b, f.a, -f.sign);
        }
        break;
      case Stage::kForward:  // b carries the chain on, with the mass of a's side behind it
        if (!next_candidate(ctx, f, f.b, c)) {
          finish(ctx);
        } else if (!f.frozen) {
          const bool w = ctx.bodies.immovable(c);
          push_frame(ctx, f.b, c, f.extra + ctx.bodies.mass[f.a], f.chain_axis, w, w ? c : kNoSlot);
        } else if (away(ctx, f.chain_axis, f.b, c) == -f.sign) {
          push_frame(ctx, c, f.b, 0.0, f.chain_axis, true, f.anchor);  // b is a wall now
        } else {
          leftover_ = true;  // on the side b leans on: not b's to push
        }
        break;
    }
  }
  if (cut_) ++ctx.stats.budget_hits;
}

void ChainResolver::push_frame(StepContext& ctx, std::uint32_t a, std::uint32_t b, double extra,
                               int axis, bool force_static, std::uint32_t anchor) {
  Frame f{};
  f.a = a;
  f.b = b;
  f.anchor = anchor;
  f.cand_begin = f.cand_end = f.cursor = static_cast<std::uint32_t>(cands_.size());
  f.extra = extra;
  f.axis = static_cast<std::int8_t>(axis);
  f.stage = Stage::kEnter;
  f.force_static = force_static;
  ++on_stack_[a];
  ++on_stack_[b];
  stack_.push_back(f);
  ctx.stats.max_depth = std::max(ctx.stats.max_depth, static_cast<std::uint32_t>(stack_.size()));
}

bool ChainResolver::enter(StepContext& ctx, Frame& f) {
  if (ctx.budget == 0) {
    cut_ = true;
    return false;
  }
  --ctx.budget;
  ++ctx.stats.resolve_calls;
  Bodies& bodies = ctx.bodies;
  visited_[f.a] = stamp_;
  if (!bodies.immovable(f.b)) visited_[f.b] = stamp_;

  const double tol = ctx.def.touch_tolerance;
  const Overlap o = overlap(bodies, f.a, f.b);
  if (o.x <= tol || o.y <= tol) return false;
  const int axis = overlap_axis(o);
  if (f.axis != kAnyAxis && axis != f.axis) {
    leftover_ = true;  // an overlap across the chaining axis: the next sweep takes it
    return false;
  }
  const double* p = ctx.pos(axis);
  const double* h = ctx.half(axis);
  const int sign = away(ctx, axis, f.b, f.a);
  f.chain_axis = static_cast<std::int8_t>(axis);
  f.sign = static_cast<std::int8_t>(sign);
  if (!f.force_static && supported_towards(axis, f.b, -sign)) {
    f.force_static = true;  // b would be pushed into its own support: it is a wall here
    f.anchor = support_anchor_[f.b];
  }
  ctx.note_push(f.a, f.b, axis, sign);

  if (f.force_static) {
    // Placed against b rather than moved by the depth: resting stacks then rebuild the same
    // positions every step instead of accumulating rounding.
    f.moved = ctx.place(f.a, axis, p[f.b] + sign * (h[f.a] + h[f.b]));
    f.backing = static_cast<std::int8_t>(-sign);
    support(axis, f.a, -sign, f.anchor);
    f.stage = Stage::kWall;
    gather_candidates(ctx, f, f.a);
    crush_check(ctx, f, f.a, f.b, sign);
    return true;
  }
  const double depth = sign * (axis == 0 ? o.x : o.y);
  const double mass_a = bodies.mass[f.a] + f.extra;
  const double mass_b = bodies.mass[f.b];
  const double moved_a = depth * (mass_b / (mass_a + mass_b));
  ctx.move(f.a, axis, moved_a);
  ctx.move(f.b, axis, moved_a - depth);
  f.moved = moved_a;
  f.stage = Stage::kBack;
  gather_candidates(ctx, f, f.a);
  return true;
}

void ChainResolver::gather_candidates(StepContext& ctx, Frame& f, std::uint32_t around) {
  const Bodies& b = ctx.bodies;
  cands_.resize(f.cand_begin);
  ctx.broadphase.for_each_candidate(b.x[around] - b.hx[around], b.y[around] - b.hy[around],
                                    b.x[around] + b.hx[around], b.y[around] + b.hy[around],
                                    [&](std::uint32_t j) {
                                      if (j != around) cands_.push_back(j);
                                    });
  f.cand_end = static_cast<std::uint32_t>(cands_.size());
  f.cursor = f.cand_begin;
}

bool ChainResolver::next_candidate(StepContext& ctx, Frame& f, std::uint32_t from,
                                   std::uint32_t& c) {
  const Bodies& bodies = ctx.bodies;
  const double tol = ctx.def.touch_tolerance;
  const bool walls_only_push = f.stage == Stage::kWall || (f.stage == Stage::kForward && f.frozen);
  while (f.cursor < f.cand_end) {
    c = cands_[f.cursor++];
    if (c == f.a || c == f.b) continue;
    const bool immovable = bodies.immovable(c);
    if (immovable && walls_only_push) continue;  // a wall meeting a wall is crush_check's case
    if (!immovable && crushed_[c]) continue;
    const Overlap o = overlap(bodies, from, c);
    if (o.x <= tol || o.y <= tol) continue;
    if (!immovable && visited_[c] == stamp_) {
      // Bodies still on the stack follow back when their frame completes; any other body
      // already in this chain keeps its overlap for the next sweep.
      if (on_stack_[c] == 0) leftover_ = true;
      continue;
    }
    return true;
  }
  return false;
}

void ChainResolver::yield_to(StepContext& ctx, Frame& f, std::uint32_t c) {
  if (ctx.budget == 0) {
    cut_ = true;
    f.cursor = f.cand_end;
    return;
  }
  --ctx.budget;
  ++ctx.stats.resolve_calls;
  const int axis = f.chain_axis;
  const int c_would_go = away(ctx, axis, f.a, c);
  if (overlap_axis(overlap(ctx.bodies, f.a, c)) != axis) {
    leftover_ = true;  // they meet across the chaining axis: the next sweep takes it
    return;
  }
  if (f.backing == -c_would_go) {
    // The wall is backed on the very side it would have to move to: squeezed between two
    // supports. It keeps its place; the overlap stays, reported.
    report_crush(ctx, f.a, f.anchor, support_anchor_[c], axis);
    f.cursor = f.cand_end;
    return;
  }
  const double* p = ctx.pos(axis);
  const double* h = ctx.half(axis);
  ctx.note_push(f.a, c, axis, -c_would_go);
  f.moved += ctx.place(f.a, axis, p[c] - c_would_go * (h[f.a] + h[c]));
  leftover_ = true;  // bodies this wall already pushed may now overlap it again
  gather_candidates(ctx, f, f.a);
}

// `body` was pushed against `wall` towards `side`; an immovable body overlapping it on that side
// along the chaining axis means it is squeezed between the two and can go nowhere: it is centred
// between them, reported, and left alone for the rest of the step.
void ChainResolver::crush_check(StepContext& ctx, Frame& f, std::uint32_t body, std::uint32_t wall,
                                int side) {
  Bodies& bodies = ctx.bodies;
  const double tol = ctx.def.touch_tolerance;
  const int axis = f.chain_axis;
  const double* p = ctx.pos(axis);
  const double* h = ctx.half(axis);
  for (std::uint32_t k = f.cand_begin; k < f.cand_end; ++k) {
    const std::uint32_t d = cands_[k];
    if (d == wall || !bodies.immovable(d)) continue;
    const Overlap o = overlap(bodies, body, d);
    if (o.x <= tol || o.y <= tol || overlap_axis(o) != axis) continue;
    if ((p[d] - p[wall]) * side <= 0.0) continue;  // d is on the wall's side, not beyond body
    const double wall_face = p[wall] + side * h[wall];
    const double blocker_face = p[d] - side * h[d];
    ctx.place(body, axis, 0.5 * (wall_face + blocker_face));
    ctx.note_push(body, d, axis, -side);
    report_crush(ctx, body, f.anchor == kNoSlot ? wall : f.anchor, d, axis);
    return;
  }
}

void ChainResolver::report_crush(StepContext& ctx, std::uint32_t body, std::uint32_t anchor,
                                 std::uint32_t blocker, int axis) {
  assert(anchor != kNoSlot && blocker != kNoSlot);
  crushed_[body] = 1;
  ctx.crushes.push_back({body, anchor, blocker, static_cast<Axis>(axis)});
  ++ctx.stats.crush_events;
}

// Pops the finished frame and hands its result to the frame that opened it.
void ChainResolver::finish(StepContext& ctx) {
  const Frame done = stack_.back();
  stack_.pop_back();
  cands_.resize(done.cand_begin);
  --on_stack_[done.a];
  --on_stack_[done.b];
  if (stack_.empty()) return;
  Frame& p = stack_.back();
  if (p.stage == Stage::kBack) {  // done.a == p.a: b follows a
    if (done.moved != 0.0) {
      ctx.move(p.b, p.chain_axis, done.moved);
      p.moved += done.moved;
    }
    if (done.backing != 0 && p.backing == 0) {
      p.backing = done.backing;
      p.anchor = done.anchor;
    }
    if (done.backing == p.sign && !p.frozen) {  // a is backed away from b, and b leans on a
      p.frozen = true;
      p.anchor = done.anchor;
      support(p.chain_axis, p.b, p.sign, done.anchor);
    }
  } else if (p.stage == Stage::kForward && !p.frozen) {  // done.a == p.b: a follows b
    if (done.moved != 0.0) {
      ctx.move(p.a, p.chain_axis, done.moved);
      p.moved += done.moved;
      leftover_ = true;  // a has moved since its own neighbours were checked
    }
    if (done.backing == -p.sign) {  // b leans on an immovable body, and a on b
      p.backing = done.backing;
      p.anchor = done.anchor;
      support(p.chain_axis, p.a, -p.sign, done.anchor);
    }
  }
}

}  // namespace chain::detail
