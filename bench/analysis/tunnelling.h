// Tunnelling: a body passing through another, judged from positions alone.
//
// Two solid boxes can meet, press into each other and part, but a box never comes out of another
// on the side opposite to the one it went in by. For each pair, the centre of one relative to the
// other moves on a segment each step; the boxes overlap while that relative centre is inside the
// box of their summed half extents. A pair is tunnelled when the relative centre leaves that box
// through the face opposite to the face it entered by, within one step (a fast body crossing a
// thin one) or over several (a box sinking through a floor), and on the way crossed the other's
// middle with at least half of the smaller box across it: a box that grazes another's corner and
// slides along its side, overlapping it a little, has not passed through it. Pairs that start the
// run overlapping have no entry face and are not judged. With rotation each box counts as the
// square inscribed in the disc its sides always contain, so a pair judged tunnelled certainly
// crossed.
#pragma once

#include "engine.h"
#include "pair_scan.h"
#include "scene.h"

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace chainbench {

struct TunnelEvent {
  std::size_t body = 0;     // the body that came out on the far side
  std::size_t through = 0;  // the body it passed through
  int step = 0;             // the state it was seen in (steps taken)
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
  // check() would; check() the pairs with a moved body, then end_step().
  void carry(const BodyState& s, std::span<const std::uint8_t> moved);

  // The first tunnelling seen, and how many were seen in all.
  const std::optional<TunnelEvent>& first() const { return first_; }
  std::uint64_t count() const { return count_; }

 private:
  // A face of the summed box: axis * 2 + (1 on the positive side); kNoFace when unknown.
  static constexpr std::int8_t kNoFace = -1;
  struct Inside {
    std::uint64_t pair;  // i << 32 | j
    std::int8_t entry;
    bool deep;  // crossed the middle across the entry face since it entered
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
  // Whether the relative centre's segment r0 -> r1 of pair (i, j) crosses the middle (r = 0)
  // along `axis` with at least half of the smaller box across the other along the other axis.
  bool deep(std::size_t i, std::size_t j, Vec2d r0, Vec2d r1, int axis) const;
  void rest(const BodyState& s, Inside& p) const;

  std::vector<Vec2d> half_;
  std::vector<Inside> inside_, next_;  // pairs overlapping after the last step / this step
  std::vector<std::uint32_t> index_;   // see index()
  std::optional<TunnelEvent> first_;
  std::uint64_t first_pair_ = 0;
  bool held_ = false;  // hold() has judged inside_ at rest since the last step that moved
  std::uint64_t count_ = 0;
};

}  // namespace chainbench
