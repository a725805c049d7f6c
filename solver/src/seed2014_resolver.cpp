// SPDX-License-Identifier: MIT
#include "seed2014_resolver.h"

#include "buffer.h"

#include <algorithm>
#include <cmath>

namespace chain::detail {

void Seed2014Resolver::resolve(StepContext& ctx, const std::vector<std::uint32_t>& creation_order) {
  assign_buffer(crushed_, ctx.bodies.size(), 0);
  // QUIRK: one grid per step, from the positions before any push (LGSpatialGrid, 1a6b023).
  ctx.broadphase.build(ctx.bodies);
  ctx.stats.passes = 1;
  near_.clear();
  for (const std::uint32_t a : creation_order) {
    // QUIRK: every neighbour, statics mixed in, so each dynamic pair is tried in both orders.
    const std::size_t begin = gather_near(ctx, a);
    const std::size_t end = near_.size();
    for (std::size_t k = begin; k < end; ++k) {
      const std::uint32_t b = near_[k];
      if (b == a) continue;
      cut_ = false;
      if (!resolve_pair(ctx, a, b, kNoSlot, 0.0, false, kAnyAxis, 1).zero()) ++ctx.stats.contacts;
      if (cut_) ++ctx.stats.budget_hits;
    }
    near_.resize(begin);
  }
}

std::size_t Seed2014Resolver::gather_near(StepContext& ctx, std::uint32_t body) {
  const std::size_t begin = near_.size();
  ctx.broadphase.for_each_stale_candidate(ctx.bodies, body, [&](std::uint32_t j) {
    if (ctx.bodies.collides(body, j)) near_.push_back(j);
  });
  const auto& id = ctx.bodies.id;
  std::sort(near_.begin() + static_cast<std::ptrdiff_t>(begin), near_.end(),
            [&](std::uint32_t i, std::uint32_t j) { return id[i] < id[j]; });
  return begin;
}

// resolveCollisionsBetween:and:ignoring:withAdditionalMass:forceStatic:alreadyAdjusted:
// collisionAxis: at HEAD. alreadyAdjusted only ever fed the tile pass, and there are no tiles.
Seed2014Resolver::Push Seed2014Resolver::resolve_pair(StepContext& ctx, std::uint32_t a,
                                                      std::uint32_t b, std::uint32_t ignore,
                                                      double additional_mass, bool force_static,
                                                      int axis, std::uint32_t depth) {
  if (ctx.budget == 0 || depth > static_cast<std::uint32_t>(ctx.def.seed_max_depth)) {
    cut_ = true;
    return {};
  }
  --ctx.budget;
  ++ctx.stats.resolve_calls;
  ctx.stats.max_depth = std::max(ctx.stats.max_depth, depth);
  Bodies& bd = ctx.bodies;

  Push r;
  const double a_min_x = bd.x(a) - bd.hx(a), a_max_x = bd.x(a) + bd.hx(a);
  const double a_min_y = bd.y(a) - bd.hy(a), a_max_y = bd.y(a) + bd.hy(a);
  const double b_min_x = bd.x(b) - bd.hx(b), b_max_x = bd.x(b) + bd.hx(b);
  const double b_min_y = bd.y(b) - bd.hy(b), b_max_y = bd.y(b) + bd.hy(b);
  // QUIRK: touching counts as overlapping (it then yields a zero push).
  const bool overlapping =
      !(a_min_x > b_max_x || a_max_x < b_min_x || a_min_y > b_max_y || a_max_y < b_min_y);
  if (overlapping) {
    // QUIRK: the direction comes from comparing edges (left edges on x, top edges on y, the
    // y-down original's top-left corner), not centres; for boxes of unequal size it can pick a
    // much longer push. Ties go to x.
    r.x = b_min_x > a_min_x ? b_min_x - a_max_x : b_max_x - a_min_x;
    r.y = b_max_y < a_max_y ? b_max_y - a_min_y : b_min_y - a_max_y;
    if (std::abs(r.y) < std::abs(r.x)) {
      r.x = 0.0;
    } else {
      r.y = 0.0;
    }
  }
  if (axis == 0) r.y = 0.0;  // the chaining axis, applied after the minimum axis is chosen
  if (axis == 1) r.x = 0.0;
  if (r.zero()) return {};
  const int push_axis = r.y != 0.0 ? 1 : 0;
  const double push = push_axis == 0 ? r.x : r.y;
  ctx.note_push(a, b, push_axis, push > 0.0 ? 1.0 : -1.0);

  const double mass_a = bd.mass[a] + additional_mass;
  const double mass_b = bd.immovable(b) ? 0.0 : bd.mass[b];
  const bool wall = force_static || bd.immovable(b);
  Push da, db;
  if (wall) {
    da = r;
  } else {
    const double ratio_a = mass_b / (mass_a + mass_b);
    const double ratio_b = ratio_a - 1.0;
    da = {ratio_a * r.x, ratio_a * r.y};
    db = {ratio_b * r.x, ratio_b * r.y};
  }
  ctx.move(a, 0, da.x);  // updateTransform: moves, and stops velocity into the push
  ctx.move(a, 1, da.y);
  if (!db.zero()) {
    ctx.move(b, 0, db.x);
    ctx.move(b, 1, db.y);
  }
  // follow-back: addToPosition, which leaves velocity and flags alone
  auto follow = [&](std::uint32_t body, Push d) {
    bd.pos(0, body) += d.x;
    bd.pos(1, body) += d.y;
    ctx.broadphase.note_move(body, bd.x(body), bd.y(body));
  };

  const std::size_t begin = gather_near(ctx, a);
  const std::size_t end = near_.size();
  if (wall) {
    count_crush(ctx, a, b, push_axis, begin);
    // QUIRK: b itself is not excluded here (it was until 3445c5e); touching makes it harmless.
    for (std::size_t k = begin; k < end; ++k) {
      const std::uint32_t c = near_[k];
      if (c == a || c == ignore || bd.immovable(c)) continue;
      resolve_pair(ctx, c, a, b, 0.0, true, push_axis, depth + 1);
    }
    near_.resize(begin);
    return da;
  }
  bool chained = false;
  for (std::size_t k = begin; k < end; ++k) {
    const std::uint32_t c = near_[k];
    if (c == a || c == b || c == ignore) continue;
    // QUIRK: only b's own mass goes along; a's additional mass is dropped on this side.
    const Push ra = resolve_pair(ctx, a, c, b, mass_b, false, push_axis, depth + 1);
    if (!ra.zero()) {
      follow(b, ra);
      db.x += ra.x, db.y += ra.y;
      chained = true;
    }
  }
  near_.resize(begin);
  // QUIRK: b's side is chained only when a's side did not chain.
  if (!chained) {
    const std::size_t b_begin = gather_near(ctx, b);
    const std::size_t b_end = near_.size();
    for (std::size_t k = b_begin; k < b_end; ++k) {
      const std::uint32_t c = near_[k];
      if (c == a || c == b || c == ignore) continue;
      const Push rb = resolve_pair(ctx, b, c, a, mass_a, false, push_axis, depth + 1);
      if (!rb.zero()) {
        follow(a, rb);
        da.x += rb.x, da.y += rb.y;
      }
    }
    near_.resize(b_begin);
  }
  return da;
}

// The 2014 engine noticed nothing here; the count makes the squeeze visible in the numbers.
void Seed2014Resolver::count_crush(StepContext& ctx, std::uint32_t body, std::uint32_t wall,
                                   int axis, std::size_t near_begin) {
  Bodies& bd = ctx.bodies;
  if (crushed_[body]) return;
  const double tol = ctx.def.touch_tolerance;
  for (std::size_t k = near_begin; k < near_.size(); ++k) {
    const std::uint32_t d = near_[k];
    if (d == wall || d == body || !bd.immovable(d)) continue;
    const Overlap o = overlap(bd, body, d);
    if (o.x <= tol || o.y <= tol || (o.x <= o.y ? 0 : 1) != axis) continue;
    crushed_[body] = 1;
    ctx.crushes.push_back({body, wall, d, static_cast<Axis>(axis)});
    ++ctx.stats.crush_events;
    return;
  }
}

}  // namespace chain::detail
