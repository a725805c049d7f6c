// Finds the pairs of bodies that may touch during a step, from positions alone, never from what an
// engine reports: every pair (at least one of them dynamic) whose boxes, each swept from where it
// was before the step to where it is after, overlap or touch. Penetration, tunnelling and the
// no_overlap expectation are all measured on these pairs, so a step costs one pass.
//
// A uniform grid about the size of most dynamic boxes holds every swept box in each cell it
// covers; a pair met in several cells is reported by the one cell holding the lower-left corner of
// the two boxes' intersection. A box that covers more than kMaxCells cells (a floor of a large
// world, a body moving far in one step) is tested against every other box instead.
//
// A scan may also hold only some of the bodies (those that moved in a step): for_each_pair then
// finds the pairs among them, and for_each_touching those between them and any other body at
// rest, so that a step in which few bodies moved costs little more than a pass over the rest.
#pragma once

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
  static constexpr std::int64_t kMaxCells = 1024;
  struct Box {
    double x0, y0, x1, y1;
  };
  struct Entry {
    std::uint32_t body;
    std::int64_t cx, cy;
  };
  std::int64_t cell(double v) const {
    return static_cast<std::int64_t>(std::floor(std::clamp(v * inv_cell_, -4.0e18, 4.0e18)));
  }
  std::uint64_t bucket(std::int64_t cx, std::int64_t cy) const;
  static bool touch(const Box& a, const Box& b) {
    return a.x0 <= b.x1 && b.x0 <= a.x1 && a.y0 <= b.y1 && b.y0 <= a.y1;
  }
  void add(std::size_t i, const BodyState& before, const BodyState& after);
  void sort_entries();
  template <class Fn>
  void report(std::uint32_t i, std::uint32_t j, Fn& fn) const {
    if (dynamic_[i] | dynamic_[j]) fn(std::min(i, j), std::max(i, j));
  }

  std::vector<Vec2d> half_;
  std::vector<Vec2d> reach_;  // half extents of the box's bounding box at any angle
  std::vector<std::uint8_t> dynamic_;
  bool rotated_ = false;
  double inv_cell_ = 1.0;
  std::vector<Box> swept_;
  std::vector<std::uint8_t> live_;   // finite position, in the scan
  std::vector<std::uint8_t> giant_;  // tested against every other box
  std::vector<std::uint32_t> giants_;
  std::vector<Entry> entries_, sorted_;
  std::vector<std::uint32_t> start_;  // per bucket, into sorted_
  std::uint64_t mask_ = 0;
  bool subset_ = false;  // holds members_ only, not every body
  std::span<const std::uint32_t> members_;
  Box bounds_{};  // of every held box that is not a giant
};

template <class Fn>
void PairScan::for_each_pair(Fn&& fn) const {
  // Pairs within a bucket of the same cell, each reported by the cell holding the lower-left
  // corner of the two boxes' intersection.
  // Bucket by bucket, walking the entries rather than the (mostly empty) table.
  for (std::uint32_t first = 0, last = 0; first < sorted_.size(); first = last) {
    last = start_[bucket(sorted_[first].cx, sorted_[first].cy) + 1];
    for (std::uint32_t k = first; k < last; ++k) {
      const Entry& e = sorted_[k];
      const Box& a = swept_[e.body];
      for (std::uint32_t m = k + 1; m < last; ++m) {
        const Entry& f = sorted_[m];
        if (f.cx != e.cx || f.cy != e.cy || f.body == e.body) continue;
        const Box& c = swept_[f.body];
        if (!touch(a, c)) continue;
        if (cell(std::max(a.x0, c.x0)) != e.cx || cell(std::max(a.y0, c.y0)) != e.cy) continue;
        report(e.body, f.body, fn);
      }
    }
  }
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
  const std::int64_t cx0 = cell(q.x0), cx1 = cell(q.x1), cy0 = cell(q.y0), cy1 = cell(q.y1);
  const double cells = (static_cast<double>(cx1) - static_cast<double>(cx0) + 1.0) *
                       (static_cast<double>(cy1) - static_cast<double>(cy0) + 1.0);
  if (cells > static_cast<double>(kMaxCells)) {  // a giant at rest: against every box held
    for (const std::uint32_t j : members_) {
      if (j != held && live_[j] && !giant_[j] && touch(q, swept_[j])) report(j, held, fn);
    }
    return;
  }
  for (std::int64_t cy = cy0; cy <= cy1; ++cy) {
    for (std::int64_t cx = cx0; cx <= cx1; ++cx) {
      const std::uint64_t b = bucket(cx, cy);
      for (std::uint32_t k = start_[b]; k < start_[b + 1]; ++k) {
        const Entry& e = sorted_[k];
        if (e.cx != cx || e.cy != cy || e.body == held) continue;
        const Box& a = swept_[e.body];
        if (!touch(q, a)) continue;
        if (cell(std::max(a.x0, q.x0)) != cx || cell(std::max(a.y0, q.y0)) != cy) continue;
        report(e.body, held, fn);
      }
    }
  }
}

}  // namespace chainbench
