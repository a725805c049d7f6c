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
// A scan may also hold only some of the bodies (those that moved in a step): for_each_pair then
// finds the pairs among them, and for_each_touching those between them and any other body at
// rest, so that a step in which few bodies moved costs little more than a pass over the rest.
#pragma once

#include "cell_table.h"
#include "engine.h"
#include "scene.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

namespace chainbench {

class PairScan {
 public:
  explicit PairScan(const Scene& scene);

  // Buckets every body's box swept from `before` to `after` (pass the same state twice for a
  // state at rest). Bodies with a non-finite position are left out.
  void build(const BodyState& before, const BodyState& after);
  // The same for the bodies `members` only (ascending); the span must outlive the scan's use.
  void build(const BodyState& before, const BodyState& after,
             std::span<const std::uint32_t> members);
  // fn(i, j), i < j, once for every pair whose swept boxes overlap or touch; call after build().
  template <class Fn>
  void for_each_pair(Fn&& fn) const;
  // fn(i, j), i < j, once for every pair of body x, at rest at its position in `s`, and a body
  // held by the scan whose swept box overlaps or touches x's box (at least one of them dynamic).
  // A body with a non-finite position meets none.
  template <class Fn>
  void for_each_touching(std::size_t x, const BodyState& s, Fn&& fn) const;

  // Overlap of i and j in state s along the axis of least penetration (m), 0 when apart. With
  // rotation, the boxes' separating axes are used.
  double depth(const BodyState& s, std::size_t i, std::size_t j) const;
  bool dynamic(std::size_t i) const { return dynamic_[i] != 0; }
  // Half extents as declared, and the box's reach from its centre on either axis at any angle.
  Vec2d half(std::size_t i) const { return half_[i]; }
  bool rotated() const { return rotated_; }

 private:
  using Box = CellTable::Box;
  static bool touch(const Box& a, const Box& b) { return CellTable::touch(a, b); }
  void add(std::size_t i, const BodyState& before, const BodyState& after);
  template <class Fn>
  void report(std::uint32_t i, std::uint32_t j, Fn& fn) const {
    if (dynamic_[i] | dynamic_[j]) fn(std::min(i, j), std::max(i, j));
  }

  std::vector<Vec2d> half_;
  std::vector<Vec2d> reach_;  // half extents of the box's bounding box at any angle
  std::vector<std::uint8_t> dynamic_;
  bool rotated_ = false;
  std::vector<Box> swept_;
  std::vector<std::uint8_t> live_;   // finite position, in the scan
  std::vector<std::uint8_t> giant_;  // tested against every other box
  std::vector<std::uint32_t> giants_;
  CellTable table_;      // the held boxes that are not giants
  bool subset_ = false;  // holds members_ only, not every body
  std::span<const std::uint32_t> members_;
  Box bounds_{};  // of every held box that is not a giant
};

template <class Fn>
void PairScan::for_each_pair(Fn&& fn) const {
  // Pairs sharing a cell, from the table, then the giants, which it does not hold.
  table_.for_each_pair(swept_, [&](std::uint32_t i, std::uint32_t j) { report(i, j, fn); });
  // Giant boxes against every other live box held, each pair once.
  auto against = [&](std::uint32_t g, std::uint32_t j) {
    if (j == g || !live_[j] || (giant_[j] && j < g)) return;
    if (touch(swept_[g], swept_[j])) report(g, j, fn);
  };
  for (const std::uint32_t g : giants_) {
    if (!subset_) {
      for (std::uint32_t j = 0; j < swept_.size(); ++j)
        against(g, j);
    } else {
      for (const std::uint32_t j : members_)
        against(g, j);
    }
  }
}

template <class Fn>
void PairScan::for_each_touching(std::size_t x, const BodyState& s, Fn&& fn) const {
  const Vec2d p = s.position[x], r = reach_[x];
  if (!std::isfinite(p.x) || !std::isfinite(p.y)) return;
  const Box q{p.x - r.x, p.y - r.y, p.x + r.x, p.y + r.y};
  const auto held = static_cast<std::uint32_t>(x);
  for (const std::uint32_t g : giants_) {
    if (g != held && touch(q, swept_[g])) report(g, held, fn);
  }
  if (!touch(q, bounds_)) return;
  const CellTable::Cells c = table_.cover(q);
  if (c.count() > CellTable::kMaxCells) {  // a giant at rest: against every box held
    for (const std::uint32_t j : members_) {
      if (j != held && live_[j] && !giant_[j] && touch(q, swept_[j])) report(j, held, fn);
    }
    return;
  }
  table_.for_each_in_cells(q, c, swept_, [&](std::uint32_t j) {
    if (j != held) report(j, held, fn);
  });
}

}  // namespace chainbench
