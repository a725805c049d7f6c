// SPDX-License-Identifier: MIT
// Checks a scene's `expect` entries against one engine's run, state by state.
//
// Every entry is judged on the states it names (the final one, or each state of its window) and
// keeps its worst: the state, the body and the value furthest from what the entry allows, so a
// failed expectation can be traced to a body and a step.
#pragma once

#include "engines/engine.h"
#include "judge/metrics.h"
#include "model/scene.h"

#include <cstdint>
#include <optional>
#include <vector>

namespace chainbench {

struct ExpectOutcome {
  std::size_t index = 0;             // in scene.expect
  std::optional<std::size_t> body;   // the body that decided, when one did
  std::optional<std::size_t> other;  // no_overlap: the body it overlapped
  int state = -1;                    // steps taken at the worst state; -1: never checked
  Vec2d position;                    // center, moved, bounds: the body's centre there
  // center, moved: distance from the expected centre; bounds: distance outside them; at_rest:
  // speed; no_overlap: depth.
  double value = 0.0;
  double error = 0.0;  // center, moved: the distance; the others: how far beyond their limit
  // Over the bodies the entry names, at the worst state: root mean square of their errors, and
  // how many they are (1 for a single body or no_overlap).
  double rms = 0.0;
  std::size_t bodies = 1;
  bool pass = true;
  // What the entry allows (center, moved: its tolerance; at_rest: its speed; no_overlap: its
  // depth; bounds: 0), how far the worst state went beyond it (negative while it holds), and
  // whether a failure is a near miss: beyond it by at most a tenth of it (bounds, which allow
  // nothing: a tenth of 5% of the body's smaller edge). Units as `value`.
  double limit = 0.0;
  double margin = 0.0;
  bool near = false;
  // on: at the worst state the body was not over the other along x (RelationJudgement::beside);
  // `value` is the gap along x, the margin the larger of it and the faces' miss, never near.
  bool beside = false;
  friend bool operator==(const ExpectOutcome&, const ExpectOutcome&) = default;
};

// Whether an entry of this kind is judged in m/s (at_rest) rather than metres.
inline bool is_speed(Expectation::Kind kind) {
  return kind == Expectation::Kind::kAtRest;
}

struct ExpectResult {
  // The largest error of the entries judged in metres (center, moved, bounds, no_overlap) and of
  // those judged in m/s (at_rest: the excess over the limit), kept apart so that neither hides
  // the other; whether each kind passed, and whether the scene has any of it.
  double max_error = 0.0;        // m
  double max_speed_error = 0.0;  // m/s
  bool pass = true;
  bool position_pass = true, speed_pass = true;
  bool has_position = false, has_speed = false;
  // Every failed entry is a near miss (ExpectOutcome::near); false when none failed.
  bool near_miss = false;
  std::vector<ExpectOutcome> entries;  // one per scene.expect entry, in order
  friend bool operator==(const ExpectResult&, const ExpectResult&) = default;
};

class ExpectationCheck {
 public:
  explicit ExpectationCheck(const Scene& scene);
  bool empty() const { return outcomes_.empty(); }
  // Whether the run must read state k: some entry checks it, or checks k + 1 for rest (speed is
  // measured over the step into a state).
  bool needs_state(int k) const;
  // Whether some no_overlap entry checks state k.
  bool needs_depth(int k) const;
  // Judges state k. `previous` is state k - 1 (null for k = 0); `deepest` the deepest overlap of
  // state k when needs_depth(k).
  void observe(int k, const BodyState& state, const BodyState* previous,
               const PairOverlap* deepest);
  // Entries whose window the run never reached (it was interrupted) count as failed.
  ExpectResult result() const;

 private:
  // Records state k's value for o; true when it is o's worst so far.
  bool judge(ExpectOutcome& o, double value, double error, bool pass, int k);

  const Scene& scene_;
  std::vector<std::size_t> dynamic_;
  std::vector<ExpectOutcome> outcomes_;
  // Per state 0..steps: needs_state() and needs_depth(), worked out once from the windows (a run
  // asks every step, and a scene may state thousands of entries).
  std::vector<std::uint8_t> needs_state_, needs_depth_;
};

}  // namespace chainbench
