// SPDX-License-Identifier: MIT
// The least a harness that judges pairs every step can cost: reading the state back, and the
// tunnel check and overlap depth of every pair with a body that moved in the step; nothing else
// (no search for the pairs, no bookkeeping). Timed beside the bare step (harness/FAMILY/SIZE/
// metrics:2), it bounds from below what the metrics of `chainbench run` can cost on that scene.
#pragma once

#include "engines/engine.h"
#include "engines/engine_spec.h"
#include "index/pair_scan.h"
#include "judge/tunnelling.h"
#include "model/scene.h"

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace chainbench {

class PairJudging {
 public:
  // Steps a twin of `spec`'s engine through `warmup` steps and `window` more, keeping for each
  // step of the window the pairs whose swept boxes touch with a body that moved (found with a
  // PairScan, outside any timing). Engines are deterministic, so an engine stepped alike
  // reaches the same states.
  PairJudging(const Scene& scene, const EngineSpec& spec, int warmup, int window);
  // Judges the pairs of the window's step k (0-based), from `before` to `after`, as the recorder
  // would; returns the sum of their depths (m), so that the work cannot be optimised away.
  double judge(int k, const BodyState& before, const BodyState& after);
  std::size_t window() const { return pairs_.size(); }
  // Pairs judged per step, on average over the window.
  double pairs_per_step() const;

 private:
  PairScan scan_;
  TunnelWatch tunnels_;
  int first_step_;
  std::vector<std::vector<std::pair<std::uint32_t, std::uint32_t>>> pairs_;
};

}  // namespace chainbench
