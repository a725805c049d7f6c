// SPDX-License-Identifier: MIT
// Skipping the steps of a world at rest (WorldDef::skip_rest).
//
// A step is a function of the bodies (centres, velocities, the definitions and drives the API
// set), dt, and one piece of state it hands the next step: the squeezes ForceStatic remembers.
// Everything else it builds (marks, near pairs, links, grids) is rebuilt or only makes it faster.
// So when a step left every movable body where it began it, at velocity +0 (in bits), having
// begun at velocity +0 (the step before ended so), nothing of the API changed the bodies since,
// and no squeeze is remembered, the next step with the same dt starts from the same state that
// step did and rebuilds the same bits: it can be skipped. Skipping changes nothing, so the step
// after it may be skipped too, until the API changes a body, dt changes or the slots are
// renumbered.
#pragma once

#include "bodies.h"

#include <bit>
#include <cstdint>
#include <cstring>

namespace chain::detail {

class Rest {
 public:
  // The API changed some body, or the slots were renumbered: the next steps are solved.
  void disturb() { still_steps_ = 0; }
  // Whether a step of dt may be skipped: the last two steps were solved still (or skipped), the
  // last of them with this dt, and the resolver remembers no squeeze.
  bool may_skip(double dt, bool remembers_squeezes) const {
    return still_steps_ >= 2 && !remembers_squeezes &&
           std::bit_cast<std::uint64_t>(dt) == std::bit_cast<std::uint64_t>(dt_);
  }
  // After a solved step of dt: whether it left every movable body where it began (Bodies::start)
  // and at velocity +0, in bits. Stops at the first body that moved, so a moving world pays
  // about nothing for it.
  void after_step(const Bodies& b, double dt) {
    for (std::uint32_t i = 0; i < b.movable_end; ++i) {
      if (std::memcmp(b.box[i].center, &b.start[i], sizeof(Point)) != 0 ||
          std::bit_cast<std::uint64_t>(b.vx[i]) != 0 ||
          std::bit_cast<std::uint64_t>(b.vy[i]) != 0) {
        still_steps_ = 0;
        return;
      }
    }
    if (still_steps_ < 2) ++still_steps_;
    dt_ = dt;
  }

 private:
  std::uint32_t still_steps_ = 0;  // solved steps in a row that left the bodies still, at most 2
  double dt_ = 0.0;                // the last of them's dt
};

}  // namespace chain::detail
