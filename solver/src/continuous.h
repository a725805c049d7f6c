// SPDX-License-Identifier: MIT
// Continuous collision for the modern variant: the bodies that moved far for their size this
// step are swept along their paths before push-out, so none passes through another.
//
// Why a swept test and not sub-steps: push-out alone fails once one step's travel passes the
// middle of what a body hits (it comes out on the far side) or the whole of it (it never meets
// it). Sub-steps small enough for a thin slab at kMaxSpeed would number in the hundreds of
// thousands; a swept box test is one closed-form time of impact per pair, at any speed and dt.
// Only fast bodies pay (motion.h says which are): a step without any costs one comparison per
// body in integration, and a step with some costs one broadphase build plus a query per fast
// body's swept box.
//
// Against static and kinematic bodies (relative motion, so kinematic ones count at any speed):
// a body's path is cut at the first face it meets that is a way in (entry_face.h: not a join
// between flush tiles); the body is placed against that face and keeps moving along it (moving
// with a kinematic body along the face's axis), as a slow body resting there would. That contact
// is recorded like a push (touching flags, velocity rule, friction). A body may slide along up to
// kMaxSlides faces a step and then stops for the rest of the step. A slow body that a fast
// kinematic body reaches is swept the same way, against everything immovable around both paths,
// and the bodies a kinematic body carries keep their order along its motion (carry.h).
// A body pressed along one axis from both sides in a step (a platform lifting it into a ceiling)
// is squeezed: it is reported as a crush event and stays where it met the second face.
//
// Against dynamic bodies: a fast dynamic body is swept against the straight-line motion of every
// other dynamic body over the step (start position to integrated position). Push-out separates a
// pair along its axis of least overlap, away from the other's centre, so it undoes a meeting
// correctly while the body has not crossed the other's centre along the axis they met on and is
// less deep along it than across it. Only where the step would end beyond that (kPushOutShare of
// it, clear of rounding) does the body's motion stop, at that depth (the rest of its step is
// dropped; it keeps its velocity); a shallower end is left as integrated, so a fast pusher pushes
// exactly as far as push-out alone makes it. Push-out then resolves the overlap as between slow
// bodies: mass split, chains, force-static backing, velocity rule. What is not promised: when both
// bodies are fast and one is stopped earlier by a third body, the other may pass where the first
// would have been; and bodies moved by pushes are not swept (a push moves a body by an overlap
// depth).
//
// Every result is computed from the positions integration left, then applied, so results do not
// depend on the order bodies are swept in.
#pragma once

#include "carry.h"
#include "chain_state.h"
#include "step_context.h"

#include <cstdint>
#include <vector>

namespace chain::detail {

class ContinuousCollision {
 public:
  // Sweeps the step's fast bodies (ctx.motion.fast()) and what they may meet. Returns true when
  // it built the broadphase (the first step after the body set changed), and moved bodies since.
  bool run(StepContext& ctx, ChainState& state);

  static constexpr int kMaxSlides = 4;

 private:
  struct Pair {
    std::uint32_t body, other;  // `body` is dynamic and swept; `other` may meet it
  };
  void gather_pairs(StepContext& ctx);
  void sweep_body(StepContext& ctx, ChainState& state, std::uint32_t body, const Pair* begin,
                  const Pair* end);
  // The step at which dynamic `body` must stop for the dynamic bodies among [begin, end): 1 if
  // none needs it.
  double dynamic_stop(const StepContext& ctx, std::uint32_t body, const Pair* begin,
                      const Pair* end) const;
  // Slides `body` from its start through [0, until] of the step along the immovable bodies in
  // walls_; returns where it ends, and the kinematic body carrying it then, if one is. A body met
  // along one axis from both sides is squeezed: it is reported crushed and stops there.
  SweptPlacement slide(StepContext& ctx, ChainState& state, std::uint32_t body, double until);

  std::vector<std::uint8_t> fast_;  // per slot: moved fast this step
  double slow_reach_ = 0.0;         // the largest move along an axis of a body not fast, m
  std::vector<Pair> pairs_;
  std::vector<std::uint32_t> by_x_;  // fast bodies by the low x of their swept boxes
  std::vector<std::uint32_t> walls_;
  std::vector<SweptPlacement> results_;
  Carry carry_;
};

}  // namespace chain::detail
