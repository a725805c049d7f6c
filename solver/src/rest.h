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

#include <algorithm>
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
  // and at velocity +0, in bits. The check stops at the first body that moved, which in a world at
  // rest is the last; after a check that found one, the next steps are taken as moving without a
  // look, 1, 3, 7 ... up to kMaxWait of them, so a moving world pays about nothing for it and one
  // that comes to rest is skipped at most kMaxWait + 2 steps later.
  void after_step(const Bodies& b, double dt) {
    if (wait_ > 0) {
      --wait_;
      still_steps_ = 0;
      return;
    }
    if (moved(b)) {
      still_steps_ = 0;
      backoff_ = std::min(2 * backoff_ + 1, kMaxWait);
      wait_ = backoff_;
      return;
    }
    backoff_ = 0;
    if (still_steps_ < 2) ++still_steps_;
    dt_ = dt;
  }

 private:
  static constexpr std::uint32_t kMaxWait = 31;

  static bool moved(const Bodies& b) {
    for (std::uint32_t i = 0; i < b.movable_end; ++i) {
      if (std::memcmp(b.box[i].center, &b.start[i], sizeof(Point)) != 0 ||
          std::bit_cast<std::uint64_t>(b.vx[i]) != 0 || std::bit_cast<std::uint64_t>(b.vy[i]) != 0)
        return true;
    }
    return false;
  }

  std::uint32_t still_steps_ = 0;  // solved steps in a row that left the bodies still, at most 2
  double dt_ = 0.0;                // the last of them's dt
  std::uint32_t backoff_ = 0;      // steps the last failed check set to go unchecked
  std::uint32_t wait_ = 0;         // of which this many are left
};

}  // namespace chain::detail
