// SPDX-License-Identifier: MIT
#include "step_context.h"

#include <algorithm>
#include <cmath>

namespace chain::detail {

double StepContext::limit_move(std::uint32_t i, int axis, double d, std::uint32_t follower,
                               Passes passes, const void* arg) const {
  const int k = axis, v = 1 - axis;
  const double sign = d > 0.0 ? 1.0 : -1.0;
  const double from = bodies.pos(k, i);
  double allowed = std::abs(d);
  // The box i sweeps on its way.
  double centre[2], half[2];
  centre[k] = from + 0.5 * d;
  half[k] = bodies.half(k, i) + 0.5 * std::abs(d);
  centre[v] = bodies.pos(v, i);
  half[v] = bodies.half(v, i);
  broadphase.for_each_in_box(
      bodies, centre[0], centre[1], half[0], half[1], 0.0, [&](std::uint32_t c) {
        if (c == i || c == follower || !bodies.collides(i, c) || (passes && passes(arg, c))) return;
        const double ahead = sign * (bodies.pos(k, c) - from);
        if (ahead <= 0.0) return;  // behind: i moves away from its centre
        const double hi = bodies.half(v, i), hc = bodies.half(v, c);
        const double across = (hi + hc) - std::abs(bodies.pos(v, i) - bodies.pos(v, c));
        if (across < 0.5 * std::min(hi, hc)) return;  // grazed
        const double full = bodies.half(k, i) + bodies.half(k, c);
        if (bodies.immovable(c) && std::abs(bodies.start_pos(k, i) - bodies.start_pos(k, c)) >=
                                       full - def.touch_tolerance) {
          // Outside it along the move when the step began: push-out takes
          // i back out through that face at any depth (entry_face.h), so
          // it only must not come out beyond.
          allowed = std::min(allowed, ahead + kPushOutShare * full);
          return;
        }
        // Deeper already than any guarded move leaves a pair, by a margin
        // rounding cannot cross: created so.
        if (ahead < 0.5 * (1.0 - kPushOutShare) * full) return;
        // Depth in c after travelling t: full - (ahead - t).
        allowed = std::min(allowed, std::max(0.0, ahead - (1.0 - kPushOutShare) * full));
      });
  return sign * allowed;
}

}  // namespace chain::detail
