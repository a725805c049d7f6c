// SPDX-License-Identifier: MIT
#include "carry.h"

#include "buffer.h"

#include <algorithm>
#include <cmath>

namespace chain::detail {
namespace {

// How far along the carrier's motion a carried body started: nearer bodies are placed first.
double ahead(const Bodies& bodies, const SweptPlacement& r) {
  return r.side * bodies.start_pos(r.axis, r.body);
}

}  // namespace

void Carry::insert_pending(const Bodies& bodies, const std::vector<SweptPlacement>& results,
                           std::size_t from, std::uint32_t r) {
  pending_.push_back(r);
  std::size_t at = pending_.size() - 1;
  const double a = ahead(bodies, results[r]);
  while (at > from) {
    const SweptPlacement& before = results[pending_[at - 1]];
    const double b = ahead(bodies, before);
    if (b < a || (b == a && before.body < results[r].body)) break;
    pending_[at] = pending_[at - 1];
    --at;
  }
  pending_[at] = r;
}

void Carry::run(StepContext& ctx, ChainState& state, std::vector<SweptPlacement>& results) {
  const Bodies& bodies = ctx.bodies;
  const double tol = ctx.def.touch_tolerance;
  entries_.clear();
  for (std::uint32_t i = 0; i < results.size(); ++i) {
    if (results[i].carrier != kNoSlot) entries_.push_back(i);
  }
  if (entries_.empty()) return;
  if (result_of_.size() != bodies.size()) assign_buffer(result_of_, bodies.size(), kNone);
  for (std::uint32_t i = 0; i < results.size(); ++i)
    result_of_[results[i].body] = i;
  std::sort(entries_.begin(), entries_.end(), [&](std::uint32_t p, std::uint32_t q) {
    const SweptPlacement &a = results[p], &b = results[q];
    if (a.carrier != b.carrier) return a.carrier < b.carrier;
    if (a.axis != b.axis) return a.axis < b.axis;
    if (a.side != b.side) return a.side < b.side;
    if (ahead(bodies, a) != ahead(bodies, b)) return ahead(bodies, a) < ahead(bodies, b);
    return a.body < b.body;
  });
  auto pos = [](const Point& p, int axis) { return axis == 0 ? p.x : p.y; };
  auto set = [](Point& p, int axis, double v) { (axis == 0 ? p.x : p.y) = v; };
  for (std::size_t g0 = 0; g0 < entries_.size();) {
    const SweptPlacement& first = results[entries_[g0]];
    const std::uint32_t carrier = first.carrier;
    const int k = first.axis, s = first.side, t = 1 - k;
    std::size_t g1 = g0;
    pending_.clear();
    while (g1 < entries_.size() && results[entries_[g1]].carrier == carrier &&
           results[entries_[g1]].axis == k && results[entries_[g1]].side == s) {
      pending_.push_back(entries_[g1++]);
    }
    placed_.clear();
    for (std::size_t q = 0; q < pending_.size(); ++q) {
      const std::uint32_t index = pending_[q];
      const std::uint32_t f = results[index].body;
      Point at = results[index].position;
      if (!state.crushed(f)) {
        // On whatever it overlaps across the axis that started nearer the carrier.
        for (const std::uint32_t g : placed_) {
          const SweptPlacement& below = results[g];
          if (s * (bodies.start_pos(k, below.body) - bodies.start_pos(k, f)) >= 0.0) continue;
          const double across = bodies.half(t, f) + bodies.half(t, below.body) -
                                std::abs(pos(at, t) - pos(below.position, t));
          if (across <= tol) continue;
          const double rest =
              pos(below.position, k) + s * (bodies.half(k, below.body) + bodies.half(k, f));
          if (s * (rest - pos(at, k)) > 0.0) set(at, k, rest);
        }
        results[index].position = at;
      }
      placed_.push_back(index);
      // Dynamic bodies continuous collision did not move that lie in f's way, from where
      // integration left it to where it is carried, come along on top of it.
      const double from = bodies.pos(k, f), to = pos(at, k);
      double centre[2], half[2];
      centre[k] = 0.5 * (from + to);
      half[k] = 0.5 * std::abs(to - from) + bodies.half(k, f);
      centre[t] = pos(at, t);
      half[t] = bodies.half(t, f);
      found_.clear();
      ctx.broadphase.for_each_in_box(bodies, centre[0], centre[1], half[0], half[1], 0.0,
                                     [&](std::uint32_t d) { found_.push_back(d); });
      std::sort(found_.begin(), found_.end());
      for (const std::uint32_t d : found_) {
        if (bodies.immovable(d) || result_of_[d] != kNone || state.crushed(d) ||
            !bodies.collides(f, d))
          continue;
        if (s * (bodies.start_pos(k, d) - bodies.start_pos(k, f)) <= 0.0) continue;  // behind
        const double across =
            bodies.half(t, f) + bodies.half(t, d) - std::abs(pos(at, t) - bodies.pos(t, d));
        const double reach = bodies.half(k, f) + bodies.half(k, d);
        if (across <= tol || s * (bodies.pos(k, d) - pos(at, k)) >= reach - tol) continue;
        Point moved{bodies.x(d), bodies.y(d)};
        set(moved, k, pos(at, k) + s * reach);
        const auto r = static_cast<std::uint32_t>(results.size());
        results.push_back({d, moved, carrier, k, s});
        result_of_[d] = r;
        ctx.note_push(d, f, k, s);
        double* vel = ctx.vel(k);
        if (ctx.def.velocity_rule == VelocityRule::kZero && vel[d] * s < 0.0) vel[d] = 0.0;
        insert_pending(bodies, results, q + 1, r);
      }
    }
    g0 = g1;
  }
  for (const SweptPlacement& r : results)
    result_of_[r.body] = kNone;
}

}  // namespace chain::detail
