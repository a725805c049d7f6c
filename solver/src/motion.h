// Integration: drives, gravity and positions for one step.
#pragma once

#include "bodies.h"
#include "broadphase.h"

#include <chain/types.h>

namespace chain::detail {

struct Motion {
  // Applies drives and gravity to velocities, moves every movable body by velocity * dt, and
  // notes every move.
  void integrate(Bodies& bodies, Broadphase& broadphase, Vec2 gravity, double dt);
};

}  // namespace chain::detail
