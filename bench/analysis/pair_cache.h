// The pairs of bodies whose swept boxes touch, for the steps in which most bodies move, found
// without building a grid every step.
//
// Each body is filed with a fat box: its swept box grown by a margin, and by twice the distance
// it moved in that step along each axis, so that a body keeping its pace stays inside it for a few
// steps. The pairs whose fat boxes touch are listed once. While every body's swept box stays
// inside its fat box, every pair whose swept boxes touch is on that list, so a step tests the
// listed pairs only. A step in which some body leaves its fat box, or its position turns finite or
// not, files every body again.
//
// Where only some bodies moved, the pairs with a moved body are read from each moved body's own
// list, and only the moved bodies are swept: a body at rest is still inside its fat box, since it
// was when it last moved.
#pragma once

#include "cell_table.h"
#include "engine.h"
#include "pair_scan.h"
#include "scene.h"

#include <cmath>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

namespace chainbench {

class PairCache {
 public:
  explicit PairCache(const Scene& scene);

  // fn(i, j), i < j, once for every pair whose boxes swept from `before` to `after` overlap or
  // touch, at least one of them dynamic and both positions finite: the pairs of
  // PairScan::build(before, after) and PairScan::for_each_pair. In an order fixed by the bodies.
  template <class Fn>
  void for_each_pair(const BodyState& before, const BodyState& after, Fn&& fn);
  // The same for the pairs with a body of `moved` (ascending; active[i] != 0 exactly for them),
  // when every other body is where it was in the state passed as `after` to the call before.
  template <class Fn>
  void for_each_pair_of(const BodyState& before, const BodyState& after,
                        std::span<const std::uint32_t> moved, std::span<const std::uint8_t> active,
                        Fn&& fn);
  // Forget the filing: the bodies moved without being swept here.
  void invalidate() { filed_ = false; }

  // How many times the bodies were filed (the first time included).
  std::uint64_t filings() const { return filings_; }
  // Pairs on the list now: pairs whose fat boxes touch.
  std::size_t listed() const { return pairs_.size(); }

 private:
  using Box = CellTable::Box;
  // Body i's box over the step into box_ (swept; at rest where it is after the step when it came
  // from a non-finite position), and whether it fits the fat box it was filed with.
  bool measure(std::size_t i, const BodyState& before, const BodyState& after) {
    live_[i] = scan_.swept(i, before, after, box_[i]);
    const Vec2d p = after.position[i];
    placed_[i] = std::isfinite(p.x) && std::isfinite(p.y);
    if (!live_[i] && placed_[i]) box_[i] = scan_.at_rest(i, after);
    const Box& s = box_[i];
    const Box& f = fat_[i];
    return placed_[i] == filed_placed_[i] &&
           (!placed_[i] || (f.x0 <= s.x0 && f.y0 <= s.y0 && s.x1 <= f.x1 && s.y1 <= f.y1));
  }
  // measure() on every body; true when every one fits.
  bool sweep(const BodyState& before, const BodyState& after);
  void file(const BodyState& before, const BodyState& after);

  PairScan scan_;  // of the fat boxes
  std::vector<Box> box_, fat_;
  // Per body: both positions of the step finite (its pairs are reported), its position after the
  // step finite (it is filed), and that as it was when filed.
  std::vector<std::uint8_t> live_, placed_, filed_placed_;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs_;
  // Per body, its partners on the list: adj_[adj_start_[i] .. adj_start_[i + 1]).
  std::vector<std::uint32_t> adj_start_, adj_;
  bool filed_ = false;
  std::uint64_t filings_ = 0;
};

template <class Fn>
void PairCache::for_each_pair(const BodyState& before, const BodyState& after, Fn&& fn) {
  if (!sweep(before, after)) file(before, after);
  for (const auto& [i, j] : pairs_) {
    if (live_[i] && live_[j] && CellTable::touch(box_[i], box_[j]))
      fn(static_cast<std::size_t>(i), static_cast<std::size_t>(j));
  }
}

template <class Fn>
void PairCache::for_each_pair_of(const BodyState& before, const BodyState& after,
                                 std::span<const std::uint32_t> moved,
                                 std::span<const std::uint8_t> active, Fn&& fn) {
  bool all_fit = filed_;
  for (const std::uint32_t m : moved)
    all_fit &= measure(m, before, after);
  if (!all_fit) {
    sweep(before, after);
    file(before, after);
  }
  for (const std::uint32_t m : moved) {
    if (!live_[m]) continue;
    for (std::uint32_t k = adj_start_[m]; k < adj_start_[m + 1]; ++k) {
      const std::uint32_t j = adj_[k];
      if (active[j] ? j < m || !live_[j] : !placed_[j]) continue;  // met from j, or not finite
      if (CellTable::touch(box_[m], active[j] ? box_[j] : scan_.at_rest(j, after)))
        fn(static_cast<std::size_t>(std::min(m, j)), static_cast<std::size_t>(std::max(m, j)));
    }
  }
}

}  // namespace chainbench
