// SPDX-License-Identifier: MIT
// How far each body's centre went from its start during a step, along either axis, which every
// move of a body notes (beside Broadphase::note_move): its box grown by that much around its
// start holds it wherever it was. Two bodies whose grown boxes do not come within a touch of each
// other cannot have met in the step:
// the islands of resting bodies (islands.h) are cut along such gaps. Pushes against static bodies
// are listed too: a static body's touching flags are those of every push against it, left-out
// islands' included.
#pragma once

#include "bodies.h"

#include "buffer.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace chain::detail {

struct StaticTouch {
  std::uint32_t body, wall;  // body pushed against static body wall,
  std::uint8_t side;         // which touching:: side of the wall
};

struct Reach {
  const Point* start = nullptr;  // Bodies::start
  // Per movable slot: the farthest the centre went from its start along either axis this step,
  // so far. Null: reach not kept.
  double* far = nullptr;
  const std::uint8_t* skipped = nullptr;  // per movable slot: left out of this step (islands.h)
  bool moved_skipped = false;             // some move this step moved a body left out of it
  std::vector<StaticTouch>* touches = nullptr;  // this step's pushes against static bodies

  // Body i was just moved to (x, y).
  void note(std::uint32_t i, double x, double y) {
    if (far == nullptr) return;
    if (skipped != nullptr && skipped[i]) [[unlikely]] {
      moved_skipped = true;
      return;
    }
    far[i] = std::max(far[i], std::max(std::abs(x - start[i].x), std::abs(y - start[i].y)));
  }
  void touch(std::uint32_t body, std::uint32_t wall, std::uint8_t side) {
    if (touches != nullptr) push_buffer(*touches, {body, wall, side});
  }
};

}  // namespace chain::detail
