// SPDX-License-Identifier: MIT
// Finds the pairs of bodies that may touch during a step, from positions alone, never from what an
// engine reports: every pair (at least one of them dynamic) whose boxes, each swept from where it
// was before the step to where it is after, overlap or touch. Penetration, tunnelling and the
// no_overlap expectation are all measured on these pairs, so a step costs one pass.
//
// A uniform grid (a CellTable) with cells about the size of most dynamic boxes holds every swept
// box in each cell it covers, and reports a pair met in several cells once. A box that covers more
// than CellTable::kMaxCells cells (a floor of a large world, a body moving far in one step) is
// tested against every other box instead.
//
// A scan may also hold boxes of its caller's (a PairCache's fat boxes), one per body.
#pragma once

#include "engines/engine.h"
#include "index/cell_table.h"
#include "model/scene.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

namespace chainbench {

class PairScan {
 public:
  using Box = CellTable::Box;

  // Cells `scale` times the size of most dynamic boxes (see cell()).
  explicit PairScan(const Scene& scene, double scale = 1.0);

  // Buckets every body's box swept from `before` to `after` (pass the same state twice for a
  // state at rest). Bodies with a non-finite position are left out.
  void build(const BodyState& before, const BodyState& after);
  // Buckets boxes[i] for every body i with live[i] != 0 (one box per body of the scene).
  void build(std::span<const Box> boxes, std::span<const std::uint8_t> live);
  // fn(i, j), i < j, once for every pair whose swept boxes overlap or touch; call after build().
  template <class Fn>
  void for_each_pair(Fn&& fn) const;

  // fn(i, j), i < j, for the pairs for_each_pair() finds in the grid: those of two boxes that
  // are not giants.
  template <class Fn>
  void for_each_pair_in_grid(Fn&& fn) const {
    table_.for_each_pair([&](std::uint32_t i, std::uint32_t j) { report(i, j, fn); });
  }
  // The held boxes too big for the grid, which for_each_pair() tests against every other box.
  std::span<const std::uint32_t> giants() const { return giants_; }
  // Whether a box covers more cells than the grid holds a box in (it would be a giant).
  bool giant(const Box& b) const { return table_.cover(b).count() > CellTable::kMaxCells; }
  // fn(j) once for every body j held whose box overlaps or touches `q`; call after build().
  template <class Fn>
  void for_each_held(const Box& q, Fn&& fn) const;

  // Overlap of i and j in state s along the axis of least penetration (m), 0 when apart. With
  // rotation, the boxes' separating axes are used.
  double depth(const BodyState& s, std::size_t i, std::size_t j) const;
  bool dynamic(std::size_t i) const { return dynamic_[i] != 0; }
  // Half extents as declared, and the box's reach from its centre on either axis at any angle.
  Vec2d half(std::size_t i) const { return half_[i]; }
  bool rotated() const { return rotated_; }
  // The side of the grid's cells, m: about the size of most dynamic boxes, times the scale.
  double cell() const { return cell_; }
  // Body i's box at rest at its position in `s`, at any angle (finite positions only).
  Box at_rest(std::size_t i, const BodyState& s) const {
    const Vec2d p = s.position[i], r = reach_[i];
    return {p.x - r.x, p.y - r.y, p.x + r.x, p.y + r.y};
  }
  // Body i's box swept from `before` to `after`, at any angle; false when a position is not finite.
  bool swept(std::size_t i, const BodyState& before, const BodyState& after, Box& out) const;

 private:
  static bool touch(const Box& a, const Box& b) { return CellTable::touch(a, b); }
  void add(std::size_t i, const BodyState& before, const BodyState& after);
  void file(std::size_t i, const Box& box);
  template <class Fn>
  void report(std::uint32_t i, std::uint32_t j, Fn& fn) const {
    if (dynamic_[i] | dynamic_[j]) fn(std::min(i, j), std::max(i, j));
  }

  std::vector<Vec2d> half_;
  std::vector<Vec2d> reach_;  // half extents of the box's bounding box at any angle
  std::vector<std::uint8_t> dynamic_;
  bool rotated_ = false;
  double cell_ = 1.0;
  std::vector<Box> swept_;
  std::vector<std::uint8_t> live_;   // finite position, in the scan
  std::vector<std::uint8_t> giant_;  // tested against every other box
  std::vector<std::uint32_t> giants_;
  CellTable table_;  // the held boxes that are not giants
};

template <class Fn>
void PairScan::for_each_pair(Fn&& fn) const {
  // Pairs sharing a cell, from the table, then the giants, which it does not hold.
  table_.for_each_pair([&](std::uint32_t i, std::uint32_t j) { report(i, j, fn); });
  // Giant boxes against every other live box held, each pair once.
  auto against = [&](std::uint32_t g, std::uint32_t j) {
    if (j == g || !live_[j] || (giant_[j] && j < g)) return;
    if (touch(swept_[g], swept_[j])) report(g, j, fn);
  };
  for (const std::uint32_t g : giants_) {
    for (std::uint32_t j = 0; j < swept_.size(); ++j)
      against(g, j);
  }
}

template <class Fn>
void PairScan::for_each_held(const Box& q, Fn&& fn) const {
  for (const std::uint32_t g : giants_) {
    if (touch(q, swept_[g])) fn(g);
  }
  const CellTable::Cells c = table_.cover(q);
  if (c.count() > CellTable::kMaxCells) {  // a giant query: against every box held
    for (std::uint32_t j = 0; j < swept_.size(); ++j) {
      if (live_[j] && !giant_[j] && touch(q, swept_[j])) fn(j);
    }
    return;
  }
  table_.for_each_in_cells(q, c, fn);
}

}  // namespace chainbench
