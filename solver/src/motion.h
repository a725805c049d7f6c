// Integration: drives, gravity and positions for one step, and where every movable body started
// (which face a body came in through is read from it).
#pragma once

#include "bodies.h"
#include "broadphase.h"

#include <chain/types.h>

namespace chain::detail {

struct Motion {
  // Applies drives and gravity to velocities, moves every movable body by velocity * dt, records
  // start positions, and notes every move.
  void integrate(Bodies& bodies, Broadphase& broadphase, Vec2 gravity, double dt);
};

}  // namespace chain::detail
