// SPDX-License-Identifier: MIT
#include "entry_face.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace chain::detail {
namespace {

constexpr double kInside = -std::numeric_limits<double>::infinity();
// Flush neighbours a face is checked against: a join is made of a few tiles, and a face with more
// counts as uncovered beyond them (a real edge is the safe answer). Those of the lowest slots are
// kept, so which ones count does not depend on the order the broadphase finds them in.
constexpr int kMaxCovers = 8;

}  // namespace

bool face_covered(const StepContext& ctx, std::uint32_t a, std::uint32_t b, int axis, int side,
                  double lo, double hi) {
  const Bodies& bodies = ctx.bodies;
  const double tol = ctx.def.touch_tolerance;
  const int u = 1 - axis;
  hi = std::max(hi, lo);
  const double face = bodies.pos(axis, b) + side * bodies.half(axis, b);
  // The face's plane, over [lo, hi]: flush neighbours touch it.
  double centre[2], half[2];
  centre[axis] = face;
  half[axis] = 0.0;
  centre[u] = 0.5 * (lo + hi);
  half[u] = 0.5 * (hi - lo);
  double from[kMaxCovers], to[kMaxCovers];
  std::uint32_t slot[kMaxCovers];
  int count = 0;
  ctx.broadphase.for_each_in_box(
      bodies, centre[0], centre[1], half[0], half[1], tol, [&](std::uint32_t j) {
        if (j == b || !bodies.immovable(j) || !bodies.collides(a, j)) return;
        const double near = bodies.pos(axis, j) - side * bodies.half(axis, j);
        if (std::abs(near - face) > tol) return;
        int k = count;
        if (count == kMaxCovers) {  // full: j takes the place of the highest slot, if lower
          k = static_cast<int>(std::max_element(slot, slot + kMaxCovers) - slot);
          if (slot[k] < j) return;
        } else {
          ++count;
        }
        slot[k] = j;
        from[k] = bodies.pos(u, j) - bodies.half(u, j);
        to[k] = bodies.pos(u, j) + bodies.half(u, j);
      });
  // Does the union of the neighbours' spans reach from lo to hi?
  double reached = lo;
  for (bool grew = true; grew && reached < hi - tol;) {
    grew = false;
    for (int k = 0; k < count; ++k) {
      if (from[k] <= reached + tol && to[k] > reached) {
        reached = to[k];
        grew = true;
      }
    }
  }
  return reached >= hi - tol;
}

Face entry_face(const StepContext& ctx, std::uint32_t a, std::uint32_t b) {
  const Bodies& bodies = ctx.bodies;
  const double tol = ctx.def.touch_tolerance;
  double entry[2], gap[2], closed[2];
  int side[2];
  bool outside[2];
  for (int k = 0; k < 2; ++k) {
    const double r0 = bodies.start_pos(k, a) - bodies.start_pos(k, b);
    const double r1 = bodies.pos(k, a) - bodies.pos(k, b);
    gap[k] = std::abs(r0) - (bodies.half(k, a) + bodies.half(k, b));
    side[k] = r0 >= 0.0 ? 1 : -1;
    outside[k] = gap[k] >= -tol;
    closed[k] = side[k] * (r0 - r1);
    entry[k] = !outside[k] ? kInside : (closed[k] > 0.0 ? std::max(gap[k], 0.0) / closed[k] : 0.0);
  }
  // How far one step's gravity moves a towards b along k (0 when it pulls away or across); only
  // the rules below that need it ask.
  auto sink = [&](int k) {
    const double g = k == 0 ? ctx.def.gravity.x : ctx.def.gravity.y;
    return std::max(-side[k] * g * bodies.gravity_scale[a] * ctx.dt * ctx.dt, 0.0);
  };
  // A face a started level with and closed on by no more than this step's gravity: a slid along it
  // (something held a up at that level until the step began).
  auto level = [&](int k) { return outside[k] && gap[k] <= tol && closed[k] <= sink(k) + tol; };
  // The same one step later: a face a was level with when the last step began, sunk below by no
  // more than that step's gravity, whose corner a touched along the other axis when this one began
  // (the tolerance hid the corner then) and moves into now. Across a gap exactly as wide as a box,
  // the box ends a step touching both corners and meets the far one only in the next step.
  // "A step ago" is read from the numbers: a body that fell from rest for one step is one sink
  // deep at the start of this one and closes by two this step (its velocity is one step's
  // gravity, and gravity adds another); a box resting beside a low step closes by one, and one
  // that fell further is deeper. Both equalities hold to rounding only.
  auto fell_level = [&](int k) {
    const int u = 1 - k;
    if (outside[k] || !outside[u] || gap[u] > tol || closed[u] <= 0.0) return false;
    const double s = sink(k), slack = tol + 1e-9 * s;
    return s > 0.0 && std::abs(-gap[k] - s) <= slack && std::abs(closed[k] - 2.0 * s) <= slack;
  };
  const Overlap o = overlap(bodies, a, b);
  if (!outside[0] && !outside[1]) {
    const int axis = overlap_axis(o);
    return {axis, bodies.pos(axis, a) >= bodies.pos(axis, b) ? 1 : -1, kInside};
  }
  if (outside[0] != outside[1]) {
    const int axis = outside[0] ? 0 : 1;
    if (fell_level(1 - axis)) return {1 - axis, side[1 - axis], 0.0};
    return {axis, side[axis], entry[axis]};
  }
  // Over a corner: a face slid along (across a gap no wider than a, out on the far ground's top,
  // not against its side); else the later crossing, unless flush neighbours cover that face where
  // a meets it.
  const int last = entry[0] != entry[1] ? (entry[0] > entry[1] ? 0 : 1) : overlap_axis(o);
  const int other = 1 - last;
  if (level(other) && !level(last)) return {other, side[other], entry[other]};
  auto covered = [&](int axis) {
    const int u = 1 - axis;
    const double lo =
        std::max(bodies.pos(u, a) - bodies.half(u, a), bodies.pos(u, b) - bodies.half(u, b));
    const double hi =
        std::min(bodies.pos(u, a) + bodies.half(u, a), bodies.pos(u, b) + bodies.half(u, b));
    return face_covered(ctx, a, b, axis, side[axis], lo, hi);
  };
  const int axis = covered(last) && !covered(other) ? other : last;
  return {axis, side[axis], entry[axis]};
}

}  // namespace chain::detail
