// SPDX-License-Identifier: MIT
// Sub-steps for large time steps (modern): a step whose gravity would sink some dynamic body by
// more than its own half extent is split into equal sub-steps that each sink it by at most that.
//
// Why: push-out reads a step from where its bodies end. A resting stack's boxes all sink g dt^2
// in a step; once that passes a box's height, the floor's push sends the bottom box up past the
// centre of the one above, which then comes out below it: a two-box stack collapsed at
// dt >= 0.33 s. Fast-body sweeps do not help, as the boxes move together. Sub-steps keep each
// sink under a half extent, as at 60 Hz; below that, nothing changes (n = 1, the same bits).
// What a step reports is that of its sub-steps together: touching flags and crush events of any
// of them, counts summed (deepest chain and the flags: the largest), stage times summed.
#pragma once

#include <chain/types.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace chain::detail {

// A sub-step's gravity sink, as a share of the half extent of the body it sinks.
inline constexpr double kMaxSinkShare = 1.0;
// At most this many sub-steps a step: gravity of 1e6 m/s^2 on 1 cm boxes at dt 1 s would ask for
// tens of thousands.
inline constexpr std::uint32_t kMaxSubsteps = 64;

// How fast gravity sinks a dynamic body against its size: the largest over the axes of
// |g_k * gravity_scale| / half_k, 1/s^2 (a step of dt sinks it rate * dt^2 half extents).
inline double sink_rate(Vec2 gravity, double gravity_scale, Vec2 half) {
  return std::abs(gravity_scale) *
         std::max(std::abs(gravity.x) / half.x, std::abs(gravity.y) / half.y);
}

// The sub-steps a step of dt takes when the fastest-sinking body's rate is `rate`.
inline std::uint32_t substep_count(double dt, double rate) {
  if (dt * dt * rate <= kMaxSinkShare) return 1;  // the common case, without a square root
  const double n = std::ceil(dt * std::sqrt(rate / kMaxSinkShare));
  return n <= 1.0 ? 1u : static_cast<std::uint32_t>(std::min<double>(n, kMaxSubsteps));
}

// Adds solved sub-step `part`'s counts to `sum` (the step's report so far).
inline void add_substep(StepStats& sum, const StepStats& part) {
  auto add = [](std::uint32_t& a, std::uint32_t b) {
    a = b > 0xffffffffu - a ? 0xffffffffu : a + b;
  };
  add(sum.passes, part.passes);
  add(sum.contacts, part.contacts);
  add(sum.resolve_calls, part.resolve_calls);
  sum.max_depth = std::max(sum.max_depth, part.max_depth);
  add(sum.budget_hits, part.budget_hits);
  add(sum.fast_bodies, part.fast_bodies);
  add(sum.swept, part.swept);
  add(sum.candidates, part.candidates);
  sum.renumbered = std::max(sum.renumbered, part.renumbered);
  sum.resting = std::max(sum.resting, part.resting);
  sum.redone = std::max(sum.redone, part.redone);
}

inline void add_substep(StepProfile& sum, const StepProfile& part) {
  for (const StepStage& stage : kStepStages)
    sum.*stage.ms += part.*stage.ms;
  sum.total += part.total;
}

}  // namespace chain::detail
