// SPDX-License-Identifier: MIT
#include "continuous.h"

#include "buffer.h"

#include "entry_face.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>

namespace chain::detail {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// The box a body covers over the step: its start and integrated boxes and everything between.
struct Swept {
  double lo[2], hi[2];
};

Swept swept(const Bodies& b, std::uint32_t i) {
  Swept s;
  for (int k = 0; k < 2; ++k) {
    const double p0 = b.start_pos(k, i), p1 = b.pos(k, i);
    s.lo[k] = std::min(p0, p1) - b.half(k, i);
    s.hi[k] = std::max(p0, p1) + b.half(k, i);
  }
  return s;
}

// When two boxes moving apart by r(t) = r + t * u (t in step fractions, from now) first overlap
// by more than the tolerance on both axes: `ext` holds their summed half extents less the
// tolerance. No hit if they overlap now, or never do, or only later than `horizon`.
struct Toi {
  bool hit = false;
  double at = 0.0;
  int axis = 0;  // the axis they met on: the last to overlap
};

Toi time_of_impact(const double r[2], const double u[2], const double ext[2], double horizon) {
  Toi toi;
  double enter = -kInfinity, leave = kInfinity;
  for (int k = 0; k < 2; ++k) {
    if (u[k] == 0.0) {
      if (std::abs(r[k]) < ext[k]) continue;  // overlapping along k all along
      return toi;
    }
    const double t1 = (-ext[k] - r[k]) / u[k], t2 = (ext[k] - r[k]) / u[k];
    const double lo = std::min(t1, t2), hi = std::max(t1, t2);
    if (lo > enter) {
      enter = lo;
      toi.axis = k;
    }
    leave = std::min(leave, hi);
  }
  toi.hit = enter >= 0.0 && enter < leave && enter <= horizon;
  toi.at = enter;
  return toi;
}

// The latest time in [toi.at, 1] (step fractions) at which f, moving relative to c by r(t) = r +
// t u, is still shallow enough for push-out to send it back the way it came in (toi.axis):
// depth along that axis at most kPushOutShare of the summed half extents there, and at most
// kPushOutShare of the overlap across. Depth grows linearly after the meeting and the overlap
// across is a tent in t, so each condition is linear on each side of the tent's peak.
double push_out_limit(const Bodies& bodies, std::uint32_t f, std::uint32_t c, const double r[2],
                      const double u[2], const Toi& toi) {
  const int k = toi.axis, v = 1 - k;
  const double side = u[k] < 0.0 ? 1.0 : -1.0;  // the side of c that f comes from
  const double full_k = bodies.half(k, f) + bodies.half(k, c);
  const double full_v = bodies.half(v, f) + bodies.half(v, c);
  // depth(t) = d0 + d1 t, d1 > 0: it closes along k.
  const double d0 = full_k - side * r[k], d1 = -side * u[k];
  const double s = kPushOutShare;
  double limit = kInfinity;
  // Each condition as a + b t <= 0.
  auto bound = [&](double a, double b) {
    if (b > 0.0) {
      limit = std::min(limit, -a / b);
    } else if (a + b * toi.at > 0.0) {
      limit = toi.at;  // never met after the meeting: stop there
    }
  };
  bound(d0 - s * full_k, d1);
  bound(d0 + s * r[v] - s * full_v, d1 + s * u[v]);  // across, where r_v(t) >= 0
  bound(d0 - s * r[v] - s * full_v, d1 - s * u[v]);  // across, where r_v(t) <= 0
  return std::max(limit, toi.at);
}

}  // namespace

bool ContinuousCollision::run(StepContext& ctx, ChainState& state) {
  const std::span<const std::uint32_t> fast = ctx.motion.fast();
  ctx.stats.fast_bodies = static_cast<std::uint32_t>(fast.size());
  if (fast.empty()) return false;
  Bodies& bodies = ctx.bodies;
  // The grid of earlier steps serves while the body set is the same: integration filed the fast
  // bodies again where they went (and any other body that moved far), so queries find them.
  const bool build = !ctx.broadphase.built();
  if (build) ctx.broadphase.build(bodies, ctx.dt, ctx.def.gravity);
  if (fast_.size() != bodies.size()) assign_buffer(fast_, bodies.size(), 0);
  for (const std::uint32_t i : fast)
    fast_[i] = 1;
  // How far any body that is not fast moved: a body whose swept box meets a fast body's swept box
  // ends within that of it. Only steps with fast bodies need it, so integration does not find it.
  // A body the step leaves out (islands.h) counts the move the step that solves it would make.
  slow_reach_ = 0.0;
  for (std::uint32_t i = 0; i < bodies.movable_end; ++i) {
    if (fast_[i]) continue;
    if (ctx.skipped != nullptr && ctx.skipped[i]) [[unlikely]] {
      slow_reach_ = std::max(slow_reach_, integrated_move(bodies, i, ctx.def.gravity, ctx.dt));
      continue;
    }
    slow_reach_ = std::max(slow_reach_, std::max(std::abs(bodies.x(i) - bodies.start[i].x),
                                                 std::abs(bodies.y(i) - bodies.start[i].y)));
  }
  gather_pairs(ctx);
  // Body by body, in slot order; candidates by slot: ties between equal times break the same way
  // for any creation order.
  std::sort(pairs_.begin(), pairs_.end(), [](const Pair& p, const Pair& q) {
    return p.body != q.body ? p.body < q.body : p.other < q.other;
  });
  results_.clear();
  for (std::size_t k = 0; k < pairs_.size();) {
    std::size_t end = k;
    while (end < pairs_.size() && pairs_[end].body == pairs_[k].body)
      ++end;
    sweep_body(ctx, state, pairs_[k].body, pairs_.data() + k, pairs_.data() + end);
    k = end;
  }
  carry_.run(ctx, state, results_);
  for (const SweptPlacement& r : results_) {
    bodies.pos(0, r.body) = r.position.x;
    bodies.pos(1, r.body) = r.position.y;
    ctx.noted(r.body);
  }
  ctx.stats.swept = static_cast<std::uint32_t>(results_.size());
  for (const std::uint32_t i : fast)
    fast_[i] = 0;
  return build;
}

void ContinuousCollision::gather_pairs(StepContext& ctx) {
  const Bodies& bodies = ctx.bodies;
  pairs_.clear();
  auto add = [&](std::uint32_t i, std::uint32_t j) {
    if (!bodies.immovable(i)) pairs_.push_back({i, j});
    if (!bodies.immovable(j)) pairs_.push_back({j, i});
  };
  const double pad = slow_reach_;
  for (const std::uint32_t f : ctx.motion.fast()) {
    const Swept s = swept(bodies, f);
    ctx.broadphase.for_each_in_box(bodies, 0.5 * (s.lo[0] + s.hi[0]), 0.5 * (s.lo[1] + s.hi[1]),
                                   0.5 * (s.hi[0] - s.lo[0]), 0.5 * (s.hi[1] - s.lo[1]), pad,
                                   [&](std::uint32_t j) {
                                     if (j == f || fast_[j] || !bodies.collides(f, j)) return;
                                     if (!bodies.immovable(f)) {
                                       pairs_.push_back({f, j});
                                     } else if (!bodies.immovable(j)) {
                                       pairs_.push_back({j, f});
                                     }
                                   });
  }
  // Fast against fast: their end boxes may lie far from each other's paths.
  by_x_.assign(ctx.motion.fast().begin(), ctx.motion.fast().end());
  auto low_x = [&](std::uint32_t i) {
    return std::min(bodies.start_pos(0, i), bodies.x(i)) - bodies.hx(i);
  };
  std::sort(by_x_.begin(), by_x_.end(), [&](std::uint32_t i, std::uint32_t j) {
    return low_x(i) != low_x(j) ? low_x(i) < low_x(j) : i < j;
  });
  for (std::size_t a = 0; a < by_x_.size(); ++a) {
    const Swept s = swept(bodies, by_x_[a]);
    for (std::size_t b = a + 1; b < by_x_.size() && low_x(by_x_[b]) <= s.hi[0]; ++b) {
      const Swept t = swept(bodies, by_x_[b]);
      if (t.lo[1] <= s.hi[1] && s.lo[1] <= t.hi[1] && bodies.collides(by_x_[a], by_x_[b]))
        add(by_x_[a], by_x_[b]);
    }
  }
}

double ContinuousCollision::dynamic_stop(const StepContext& ctx, std::uint32_t f, const Pair* begin,
                                         const Pair* end) const {
  const Bodies& bodies = ctx.bodies;
  const double tol = ctx.def.touch_tolerance;
  double stop = 1.0;
  for (const Pair* p = begin; p != end; ++p) {
    const std::uint32_t c = p->other;
    if (bodies.immovable(c)) continue;
    double r[2], u[2], ext[2];
    for (int k = 0; k < 2; ++k) {
      r[k] = bodies.start_pos(k, f) - bodies.start_pos(k, c);
      u[k] = (bodies.pos(k, f) - bodies.pos(k, c)) - r[k];
      ext[k] = std::max(0.0, bodies.half(k, f) + bodies.half(k, c) - tol);
    }
    const Toi toi = time_of_impact(r, u, ext, 1.0);
    if (!toi.hit) continue;
    const double until = push_out_limit(bodies, f, c, r, u, toi);
    if (until < 1.0) stop = std::min(stop, until);  // else push-out takes the step's end as it is
  }
  return stop;
}

SweptPlacement ContinuousCollision::slide(StepContext& ctx, ChainState& state, std::uint32_t f,
                                          double until) {
  Bodies& bodies = ctx.bodies;
  const double tol = ctx.def.touch_tolerance;
  double p[2] = {bodies.start_pos(0, f), bodies.start_pos(1, f)};
  double w[2] = {bodies.x(f) - p[0], bodies.y(f) - p[1]};  // per whole step
  double now = 0.0;
  std::uint32_t met[2] = {kNoSlot, kNoSlot};  // per axis, the face f is against, and its side
  int met_side[2] = {0, 0};
  // Where f ends, and the kinematic body pushing it along, if one is.
  auto result = [&] {
    SweptPlacement r{f, {p[0], p[1]}};
    for (int k = 0; k < 2; ++k) {
      const std::uint32_t c = met[k];
      if (c == kNoSlot || c >= bodies.movable_end) continue;
      if ((bodies.pos(k, c) - bodies.start_pos(k, c)) * met_side[k] > 0.0) {
        r.carrier = c, r.axis = k, r.side = met_side[k];
        break;
      }
    }
    return r;
  };
  for (int slides = 0; slides < kMaxSlides; ++slides) {
    Toi first;
    first.at = kInfinity;
    std::uint32_t wall = kNoSlot;
    int first_side = 0;
    for (const std::uint32_t c : walls_) {
      if (!bodies.collides(f, c)) continue;
      double r[2], u[2], ext[2], d[2];
      for (int k = 0; k < 2; ++k) {
        d[k] = bodies.pos(k, c) - bodies.start_pos(k, c);
        r[k] = p[k] - (bodies.start_pos(k, c) + now * d[k]);
        u[k] = w[k] - d[k];
        ext[k] = std::max(0.0, bodies.half(k, f) + bodies.half(k, c) - tol);
      }
      const Toi toi = time_of_impact(r, u, ext, until - now);
      if (!toi.hit || toi.at >= first.at) continue;
      const int k = toi.axis, v = 1 - k;
      const int side = u[k] < 0.0 ? 1 : -1;
      // Where f meets the face along the other axis, in end-of-step coordinates (the face and its
      // flush neighbours are looked up there).
      const double meet = bodies.pos(v, c) + r[v] + toi.at * u[v];
      const double lo = std::max(meet - bodies.half(v, f), bodies.pos(v, c) - bodies.half(v, c));
      const double hi = std::min(meet + bodies.half(v, f), bodies.pos(v, c) + bodies.half(v, c));
      if (face_covered(ctx, f, c, k, side, lo, hi)) continue;  // a join: it slides on over it
      first = toi;
      wall = c;
      first_side = side;
    }
    if (wall == kNoSlot) {
      for (int k = 0; k < 2; ++k)
        p[k] += (until - now) * w[k];
      return result();
    }
    int k = first.axis;
    // A face f slid along to meet this one (entry_face.h's rule): level with it when this slide
    // began, or a sink below it and falling from it one step, and moving towards it by gravity
    // alone. Then f meets that face, not this one: across a gap no wider than itself it comes out
    // on the far ground's top, as a slow body does.
    {
      const int v = 1 - k;
      const double dv = bodies.pos(v, wall) - bodies.start_pos(v, wall);
      const double rv = p[v] - (bodies.start_pos(v, wall) + now * dv);
      const int side = rv >= 0.0 ? 1 : -1;
      const double gap = std::abs(rv) - (bodies.half(v, f) + bodies.half(v, wall));
      const double closing = -side * (w[v] - dv);  // per whole step
      const double g = v == 0 ? ctx.def.gravity.x : ctx.def.gravity.y;
      const double sink = std::max(-side * g * bodies.gravity_scale[f] * ctx.dt * ctx.dt, 0.0);
      const double slack = tol + 1e-9 * sink;
      const bool level = std::abs(gap) <= tol && closing <= sink + tol;
      // Falling from it: touching its corner along k when this slide began, as entry_face's rule.
      const double dk = bodies.pos(k, wall) - bodies.start_pos(k, wall);
      const double rk = p[k] - (bodies.start_pos(k, wall) + now * dk);
      const double gap_k = std::abs(rk) - (bodies.half(k, f) + bodies.half(k, wall));
      const bool fell = sink > 0.0 && std::abs(gap_k) <= tol && std::abs(-gap - sink) <= slack &&
                        std::abs(closing - 2.0 * sink) <= slack;
      if (level || fell) {
        k = v;
        first_side = side;
      }
    }
    now += first.at;
    for (int j = 0; j < 2; ++j)
      p[j] += first.at * w[j];
    const double d = bodies.pos(k, wall) - bodies.start_pos(k, wall);
    // Against the face, exactly, then along it: moving with the wall along its axis.
    p[k] = bodies.start_pos(k, wall) + now * d +
           first_side * (bodies.half(k, f) + bodies.half(k, wall));
    w[k] = d;
    ctx.note_push(f, wall, k, first_side);
    double* vel = ctx.vel(k);
    if (ctx.def.velocity_rule == VelocityRule::kZero && vel[f] * first_side < 0.0) vel[f] = 0.0;
    if (met[k] != kNoSlot && met_side[k] == -first_side) {
      state.report_crush(ctx, f, met[k], wall, k);  // pressed into wall by what it met first
      return SweptPlacement{f, {p[0], p[1]}};
    }
    met[k] = wall;
    met_side[k] = first_side;
  }
  return result();  // out of slides: it stops where it met the last face
}

void ContinuousCollision::sweep_body(StepContext& ctx, ChainState& state, std::uint32_t f,
                                     const Pair* begin, const Pair* end) {
  const Bodies& bodies = ctx.bodies;
  const double until = fast_[f] ? dynamic_stop(ctx, f, begin, end) : 1.0;
  // The immovable bodies f may meet: its own candidates, and, when a fast kinematic body may
  // carry it, everything immovable around that body's path too.
  walls_.clear();
  bool carried = false;
  Swept region = swept(bodies, f);
  for (const Pair* p = begin; p != end; ++p) {
    if (!bodies.immovable(p->other)) continue;
    walls_.push_back(p->other);
    if (!fast_[p->other]) continue;
    carried = true;
    const Swept s = swept(bodies, p->other);
    for (int k = 0; k < 2; ++k) {
      region.lo[k] = std::min(region.lo[k], s.lo[k]);
      region.hi[k] = std::max(region.hi[k], s.hi[k]);
    }
  }
  if (carried) {
    ctx.broadphase.for_each_in_box(
        bodies, 0.5 * (region.lo[0] + region.hi[0]), 0.5 * (region.lo[1] + region.hi[1]),
        0.5 * (region.hi[0] - region.lo[0]), 0.5 * (region.hi[1] - region.lo[1]), slow_reach_,
        [&](std::uint32_t j) {
          if (bodies.immovable(j)) walls_.push_back(j);
        });
    std::sort(walls_.begin(), walls_.end());
    walls_.erase(std::unique(walls_.begin(), walls_.end()), walls_.end());
  }
  if (walls_.empty() && until >= 1.0) return;
  const SweptPlacement r = slide(ctx, state, f, until);
  if (r.position.x != bodies.x(f) || r.position.y != bodies.y(f) || r.carrier != kNoSlot)
    results_.push_back(r);
}

}  // namespace chain::detail
