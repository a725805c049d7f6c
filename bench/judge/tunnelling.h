// SPDX-License-Identifier: MIT
// Tunnelling: a body passing through another, judged from positions alone.
//
// Two solid boxes can meet, press into each other and part, but the centre of one never goes into
// the other and comes out by another face. For each pair, the centre of one relative to the other
// moves on a segment each step. A pair is tunnelled when either body's centre, having gone into
// the other's box (closed: a centre running along a face counts, such as a body grazing along the
// seam between two touching boxes, which is a face of both), leaves it through any face other
// than the one it came in by, within one step (a fast body crossing a thin one) or over several
// (a box sinking through a floor, or one slid along inside a block and out at its far end). A box
// that grazes another's corner and slides along its side has not: its centre never went in. Faces
// are judged with an allowance for rounding (a few units in the last place of the coordinates), so
// that a centre placed on a seam is on it. Pairs whose centres start the run inside have no entry
// face and are not judged until they leave; a pair counts once a visit. With rotation each box
// counts as the square inscribed in the disc its sides always contain, so a pair judged tunnelled
// certainly crossed.
#pragma once

#include "engines/engine.h"
#include "index/pair_scan.h"
#include "model/scene.h"

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace chainbench {

struct TunnelEvent {
  std::size_t body = 0;     // the body that came out on the far side
  std::size_t through = 0;  // the body it passed through
  int step = 0;             // the state it was seen in (steps taken)
  friend bool operator==(const TunnelEvent&, const TunnelEvent&) = default;
};

class TunnelWatch {
 public:
  explicit TunnelWatch(const Scene& scene);
  // Judges pair (i, j) over the step from `before` to `after` (state `step`); call it for every
  // pair a PairScan finds in that step, then end_step().
  void check(const BodyState& before, const BodyState& after, std::size_t i, std::size_t j,
             int step);
  void end_step();
  // The step from the last state to `s` moved no body: the same as check() on every pair of that
  // step and end_step(), without the pairs.
  void hold(const BodyState& s);
  // The step to `s` moved only the bodies flagged in `moved`: carries the pairs of the others as
  // check() would; check() the pairs with a moved body, then end_step(). (A pair that did not
  // move keeps its record as it is: no state is needed, the argument stays for symmetry.)
  void carry(const BodyState& s, std::span<const std::uint8_t> moved);

  // The first tunnelling seen, and how many were seen in all.
  const std::optional<TunnelEvent>& first() const { return first_; }
  std::uint64_t count() const { return count_; }

 private:
  // A face of a box: axis * 2 + (1 on the positive side); kNoFace: inside, the face unknown (it
  // started there); kOut: not inside.
  static constexpr std::int8_t kNoFace = -1;
  static constexpr std::int8_t kOut = -2;
  struct Inside {
    std::uint64_t pair;  // i << 32 | j
    std::int8_t in_j;    // i's centre in j's box: the face it came in by, kNoFace or kOut
    std::int8_t in_i;    // j's centre in i's box, likewise
    bool counted;        // this visit was counted as a tunnelling already
  };
  // The pair's entry in inside_, through index_; null when it was not inside after the last step.
  const Inside* find(std::uint64_t pair) const;
  // Fills index_ for inside_: an open-addressing table of inside_ positions + 1 (0: empty), at
  // most half full, so that a step looks each pair up in O(1) rather than sorting and searching.
  void index();
  std::size_t home(std::uint64_t pair) const {
    const std::uint64_t h = pair * 0x9E3779B97F4A7C15ull;
    return static_cast<std::size_t>(h ^ (h >> 32)) & (index_.size() - 1);
  }
  // Follows a centre's segment r0 -> r1 against the box of half extents h about the origin:
  // `entry` (as Inside::in_j) becomes its state after the step; true when it left through a face
  // other than its entry face.
  static bool follow(Vec2d r0, Vec2d r1, Vec2d h, std::int8_t& entry);

  std::vector<Vec2d> half_;
  std::vector<Inside> inside_, next_;  // pairs overlapping after the last step / this step
  std::vector<std::uint32_t> index_;   // see index()
  std::optional<TunnelEvent> first_;
  std::uint64_t first_pair_ = 0;
  std::uint64_t count_ = 0;
};

}  // namespace chainbench
