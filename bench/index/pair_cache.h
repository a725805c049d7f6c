// SPDX-License-Identifier: MIT
// The pairs of bodies whose swept boxes touch, for the steps in which bodies move, found without
// building a grid every step.
//
// Each body is filed with a fat box: its swept box grown by a margin, and by twice the distance
// it moved in that step along each axis, so that a body keeping its pace stays inside it for a few
// steps. The pairs whose fat boxes touch are listed once. While every body's swept box stays
// inside its fat box, every pair whose swept boxes touch is on that list, so a step tests the
// listed pairs only. A body that leaves its fat box (or whose position turns finite or not) is
// given a new one and becomes loose: its pairs are found again, against the fat boxes in the grid
// of the last filing and those of the other loose bodies, and kept on a list of their own. When
// more than a sixty-fourth of the bodies (and at least 16) would be loose, or a body's new fat
// box would be a giant, every body is filed again.
//
// A fat box too big for the grid (a body thrown far in one step) is a giant: its pairs are not
// listed, which would hold one pair per body for every giant, but tested against every body
// each step, as PairScan does.
//
// Where only some bodies moved, the pairs with a moved body are read from each moved body's own
// list, and only the moved bodies are measured: a body at rest is still inside its fat box, since
// it was when it last moved.
//
// Following a Presence (bodies that come and go), a body out of the world after a step is neither
// filed nor reported, as a body whose position is not finite, and one that entered in the step is
// measured at rest where it entered: what the state before held for it was no position of its.
// Bodies that enter or leave must be among the moved bodies of their step.
#pragma once

#include "engines/engine.h"
#include "index/cell_table.h"
#include "index/pair_scan.h"
#include "index/presence.h"
#include "model/scene.h"

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
  // Reports only the bodies `presence` has in the world (its state being that of each step's
  // `after`); it must outlive the cache.
  void follow(const Presence& presence) { presence_ = &presence; }
  // Forget the filing: the bodies moved without being measured here.
  void invalidate() { filed_ = false; }

  // How many times every body was filed (the first time included), and how many times a single
  // body was given a new fat box.
  std::uint64_t filings() const { return filings_; }
  std::uint64_t refits() const { return refits_; }
  // The scan the fat boxes are filed in, whose per-body constants (PairScan::depth, half,
  // dynamic, rotated) are the scene's: callers judge pairs with it instead of a scan of their own.
  const PairScan& scan() const { return scan_; }
  // Pairs held on the lists now (giants' pairs are never held).
  std::size_t listed() const { return pairs_.size() + loose_pairs_.size(); }

 private:
  using Box = CellTable::Box;
  using Pair = std::pair<std::uint32_t, std::uint32_t>;
  // Body i's box over the step into box_ (swept; at rest where it is after the step when it came
  // from a non-finite position), and whether it fits the fat box it was filed with.
  bool measure(std::size_t i, const BodyState& before, const BodyState& after) {
    const Vec2d p = after.position[i];
    if (presence_ && !presence_->stepped(i)) {  // entered in the step, or out of the world
      placed_[i] = presence_->in(i) && std::isfinite(p.x) && std::isfinite(p.y);
      live_[i] = placed_[i];
      if (placed_[i]) box_[i] = scan_.at_rest(i, after);
    } else {
      live_[i] = scan_.swept(i, before, after, box_[i]);
      placed_[i] = std::isfinite(p.x) && std::isfinite(p.y);
      if (!live_[i] && placed_[i]) box_[i] = scan_.at_rest(i, after);
    }
    const Box& s = box_[i];
    const Box& f = fat_[i];
    return placed_[i] == filed_placed_[i] &&
           (!placed_[i] || (f.x0 <= s.x0 && f.y0 <= s.y0 && s.x1 <= f.x1 && s.y1 <= f.y1));
  }
  // Body i's fat box, from its box measured over the step.
  Box fatten(std::size_t i, const BodyState& before, const BodyState& after) const;
  // measure() on `bodies` (every body when empty), refitting those that left their fat box; false
  // when so many have that every body must be filed again.
  bool measure_all(std::span<const std::uint32_t> bodies, const BodyState& before,
                   const BodyState& after);
  // Gives the bodies of refit_ new fat boxes and finds their pairs again.
  void refit(const BodyState& before, const BodyState& after);
  void file(const BodyState& before, const BodyState& after);
  void add(std::uint32_t i, std::uint32_t j) {
    if (scan_.dynamic(i) || scan_.dynamic(j))
      loose_pairs_.emplace_back(std::min(i, j), std::max(i, j));
  }

  // Cells of twice the size of most boxes: a fat box then covers about three cells rather than
  // six, which halves the entries a filing sorts, for about as many boxes compared.
  static constexpr double kCellScale = 2.0;
  PairScan scan_;  // of the fat boxes, as last filed
  std::vector<Box> box_, fat_;
  // Per body: both positions of the step finite (its pairs are reported), its position after the
  // step finite (it is filed), and that as it was when filed.
  std::vector<std::uint8_t> live_, placed_, filed_placed_;
  std::vector<Pair> pairs_;  // whose fat boxes touched when filed, giants' left out
  // Per body, its partners on that list: adj_[adj_start_[i] .. adj_start_[i + 1]).
  std::vector<std::size_t> adj_start_;
  std::vector<std::uint32_t> adj_;
  std::vector<std::uint32_t> giants_;  // bodies whose fat box was a giant when filed
  std::vector<std::uint8_t> giant_;    // per body: in giants_
  // Bodies given a new fat box since the filing, and the pairs with one of them whose fat boxes
  // touch: pairs_ and adj_ hold stale pairs of theirs, which are skipped.
  std::vector<std::uint8_t> loose_;
  std::vector<std::uint32_t> loose_list_;
  std::vector<std::uint8_t> refitting_;  // per body: in refit_
  std::vector<std::uint32_t> refit_;     // bodies that left their fat box in this step
  std::vector<Pair> loose_pairs_;
  bool filed_ = false;
  const Presence* presence_ = nullptr;
  std::uint64_t filings_ = 0, refits_ = 0;
};

template <class Fn>
void PairCache::for_each_pair(const BodyState& before, const BodyState& after, Fn&& fn) {
  if (!measure_all({}, before, after)) file(before, after);
  auto report = [&](const Pair& p) {
    if (live_[p.first] && live_[p.second] && CellTable::touch(box_[p.first], box_[p.second]))
      fn(static_cast<std::size_t>(p.first), static_cast<std::size_t>(p.second));
  };
  for (const Pair& p : pairs_) {
    if (!loose_[p.first] && !loose_[p.second]) report(p);
  }
  for (const Pair& p : loose_pairs_)
    report(p);
  // A giant against every body that is not loose (a loose body's pairs with it are listed), each
  // pair of two giants from the lower.
  for (const std::uint32_t g : giants_) {
    if (loose_[g]) continue;
    for (std::uint32_t j = 0; j < box_.size(); ++j) {
      if (j == g || loose_[j] || (giant_[j] && j < g)) continue;
      if (scan_.dynamic(g) || scan_.dynamic(j)) report({std::min(g, j), std::max(g, j)});
    }
  }
}

template <class Fn>
void PairCache::for_each_pair_of(const BodyState& before, const BodyState& after,
                                 std::span<const std::uint32_t> moved,
                                 std::span<const std::uint8_t> active, Fn&& fn) {
  if (!measure_all(moved, before, after)) {
    measure_all({}, before, after);
    file(before, after);
  }
  // A body at rest is read where it stands, and counts if its position is finite.
  auto box = [&](std::uint32_t i) { return active[i] ? box_[i] : scan_.at_rest(i, after); };
  auto counts = [&](std::uint32_t i) { return active[i] ? live_[i] != 0 : placed_[i] != 0; };
  auto meet = [&](std::uint32_t m, std::uint32_t j) {
    if (CellTable::touch(box_[m], box(j)) && (scan_.dynamic(m) || scan_.dynamic(j)))
      fn(static_cast<std::size_t>(std::min(m, j)), static_cast<std::size_t>(std::max(m, j)));
  };
  for (const std::uint32_t m : moved) {
    if (!live_[m] || loose_[m]) continue;
    if (giant_[m]) {  // against every body that is not loose; two moved giants from the lower
      for (std::uint32_t j = 0; j < box_.size(); ++j) {
        if (j == m || loose_[j] || (active[j] && giant_[j] && j < m) || !counts(j)) continue;
        meet(m, j);
      }
      continue;
    }
    for (const std::uint32_t g : giants_) {  // a moved giant meets m itself
      if (!loose_[g] && !active[g] && counts(g)) meet(m, g);
    }
    for (std::size_t k = adj_start_[m]; k < adj_start_[m + 1]; ++k) {
      const std::uint32_t j = adj_[k];
      if (loose_[j] || (active[j] && j < m) || !counts(j)) continue;  // elsewhere, or met from j
      if (CellTable::touch(box_[m], box(j)))
        fn(static_cast<std::size_t>(std::min(m, j)), static_cast<std::size_t>(std::max(m, j)));
    }
  }
  for (const auto& [i, j] : loose_pairs_) {
    if ((active[i] || active[j]) && counts(i) && counts(j) && CellTable::touch(box(i), box(j)))
      fn(static_cast<std::size_t>(i), static_cast<std::size_t>(j));
  }
}

}  // namespace chainbench
