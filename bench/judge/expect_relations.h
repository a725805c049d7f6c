// SPDX-License-Identifier: MIT
// The expectations that relate a body to others (above, below, on, squeezed) and no_overlap
// limited to named bodies, judged from one state's positions so that every engine can be checked.
//
// Faces are those of each box's axis-aligned extent at its angle (its declared half extents when
// the scene does not rotate). A non-finite position fails with an infinite value.
#pragma once

#include "engines/engine.h"
#include "judge/expectations.h"
#include "judge/metrics.h"
#include "model/scene.h"

#include <optional>
#include <string>

namespace chainbench {

struct RelationJudgement {
  // above/below: how far the face is beyond the other's face (negative: a gap); on: the distance
  // between the bottom face and the other's top face; squeezed: the wider gap of the tighter pair
  // of opposite sides (0 where they touch or overlap). All in metres.
  double value = 0.0;
  double error = 0.0;  // how far beyond `tolerance` (metres), 0 when it holds
  bool pass = true;
  std::optional<std::size_t> other;  // the body that decided
  // on: the body is not over the other along x (their x extents only touch, or part); `value`
  // is then the gap between them along x (0 where they touch), and the entry fails whatever
  // the faces' distance.
  bool beside = false;
};

// Judges e (is_relation(e.kind)) on state s, state number k: a squeeze counts only the static and
// kinematic bodies in the world in that state (validate() keeps the bodies e names alive there).
RelationJudgement judge_relation(const Scene& scene, const Expectation& e, const BodyState& s,
                                 int k);

// The deepest overlap in s (state number k) among the pairs of e.bodies in the world then (any
// kinds), with a and b its bodies; depth 0 when none overlap.
PairOverlap deepest_among(const Scene& scene, const Expectation& e, const BodyState& s, int k);

// The failure of a relation entry in words, as verdict.cpp's describe() words the others.
std::string describe_relation(const Scene& scene, const ExpectOutcome& o);

}  // namespace chainbench
