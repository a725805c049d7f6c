// Integration: drives, gravity and positions for one step, and what the rest of the step needs
// to know about it: where every movable body started, which bodies moved far for their size
// (the sweep takes those), and the velocities before push-out (friction weighs contacts by the
// momentum push-out took).
#pragma once

#include "bodies.h"
#include "broadphase.h"

#include <chain/types.h>

#include <cstdint>
#include <vector>

namespace chain::detail {

// A dynamic body is fast when a step moves it more than this share of its half extent along an
// axis: two slow dynamic bodies then close by less than half their summed half extents, so their
// centres never cross and least-overlap push-out separates them the right way. A kinematic body
// is fast past its whole half extent: a slow kinematic body and a slow dynamic one close by less
// than their summed half extents, so neither passes through the other, and the face rule
// (entry_face.h) resolves any overlap short of that.
inline constexpr double kFastDynamicShare = 0.5;
inline constexpr double kFastKinematicShare = 1.0;

struct Motion {
  // Movable slots that moved fast this step, ascending (filled when sweeping is on).
  std::vector<std::uint32_t> fast;
  // The largest move along an axis of any movable body that is not fast, m.
  double slow_reach = 0.0;
  // Per dynamic slot, the velocity after drives and gravity (filled when keeping velocities).
  std::vector<Point> pre_velocity;

  // Applies drives and gravity to velocities, moves every movable body by velocity * dt, records
  // start positions (and, as asked, the fast bodies and the velocities), and notes every move.
  void integrate(Bodies& bodies, Broadphase& broadphase, Vec2 gravity, double dt, bool find_fast,
                 bool keep_velocities);
};

}  // namespace chain::detail
