// SPDX-License-Identifier: MIT
// Bodies that a fast kinematic body carries keep their order along its motion.
//
// Continuous collision (continuous.h) places a body that a fast kinematic body reaches against that
// body's face and moves it along. Placed one by one, a stack on a platform rising several box
// heights a step would land all its boxes on the platform's face, inside each other, and push-out
// would then shove them apart sideways. So the bodies one kinematic body carries along an axis are
// placed nearest first, each resting on those placed before it that it overlaps across the axis;
// and a dynamic body in a carried body's way (one that overhangs the platform, say) is carried on
// top of it in turn, as force-static propagation would push it. Carried bodies are not swept
// against static bodies beyond this: a stack carried into a ceiling is left overlapping it, for
// push-out and its crush reports.
#pragma once

#include "chain_state.h"
#include "step_context.h"

#include <cstdint>
#include <vector>

namespace chain::detail {

// Where continuous collision put a body, and the kinematic body carrying it, if any: `carrier`
// moves it along `axis`, pushing from the body's side -`side`.
struct SweptPlacement {
  std::uint32_t body;
  Point position;
  std::uint32_t carrier = kNoSlot;
  int axis = 0, side = 0;
};

class Carry {
 public:
  // Stacks the carried bodies among `results` (results not applied yet: bodies are where
  // integration left them), adding a result for every body they carry on.
  void run(StepContext& ctx, ChainState& state, std::vector<SweptPlacement>& results);

 private:
  static constexpr std::uint32_t kNone = 0xffffffffu;
  // Insert result index r into pending_[from, end) by how far ahead along the motion it started.
  void insert_pending(const Bodies& bodies, const std::vector<SweptPlacement>& results,
                      std::size_t from, std::uint32_t r);

  std::vector<std::uint32_t> result_of_;  // per slot: its result's index, kNone if none
  std::vector<std::uint32_t> entries_, pending_, placed_, found_;
};

}  // namespace chain::detail
