// SPDX-License-Identifier: MIT
#include "index/pair_cache.h"

#include <algorithm>
#include <cmath>

namespace chainbench {

PairCache::PairCache(const Scene& scene) : scan_(scene, kCellScale) {
  const std::size_t n = scene.bodies.size();
  box_.resize(n);
  fat_.resize(n);
  live_.assign(n, 0);
  placed_.assign(n, 0);
  filed_placed_.assign(n, 0);
  loose_.assign(n, 0);
  refitting_.assign(n, 0);
  giant_.assign(n, 0);
}

PairCache::Box PairCache::fatten(std::size_t i, const BodyState& before,
                                 const BodyState& after) const {
  // A quarter of a cell: a few more pairs on the list than touch, and a body that starts to move
  // stays filed for a few steps. The distance moved keeps a steady mover filed for about two
  // steps more than that.
  double gx = 0.25 / kCellScale * scan_.cell(), gy = gx;
  if (live_[i] && (!presence_ || presence_->stepped(i))) {
    gx += 2.0 * std::abs(after.position[i].x - before.position[i].x);
    gy += 2.0 * std::abs(after.position[i].y - before.position[i].y);
  }
  const Box& s = box_[i];
  return {s.x0 - gx, s.y0 - gy, s.x1 + gx, s.y1 + gy};
}

bool PairCache::measure_all(std::span<const std::uint32_t> bodies, const BodyState& before,
                            const BodyState& after) {
  refit_.clear();
  auto one = [&](std::uint32_t i) {
    if (!measure(i, before, after)) refit_.push_back(i);
  };
  if (bodies.empty()) {
    for (std::uint32_t i = 0; i < box_.size(); ++i)
      one(i);
  } else {
    for (const std::uint32_t i : bodies)
      one(i);
  }
  if (!filed_) return false;
  if (refit_.empty()) return true;
  if (loose_list_.size() + refit_.size() > std::max<std::size_t>(16, box_.size() / 64))
    return false;
  for (const std::uint32_t i : refit_) {  // a giant's pairs are found by filing, never listed
    if (placed_[i] && scan_.giant(fatten(i, before, after))) return false;
  }
  refit(before, after);
  return true;
}

void PairCache::refit(const BodyState& before, const BodyState& after) {
  refits_ += refit_.size();
  for (const std::uint32_t i : refit_) {
    refitting_[i] = 1;
    if (!loose_[i]) loose_[i] = 1, loose_list_.push_back(i);
    filed_placed_[i] = placed_[i];
    if (placed_[i]) fat_[i] = fatten(i, before, after);
  }
  std::erase_if(loose_pairs_,
                [&](const Pair& p) { return refitting_[p.first] || refitting_[p.second]; });
  for (const std::uint32_t i : refit_) {
    if (!placed_[i]) continue;
    // Against the fat boxes as filed, of the bodies that are not loose (the grid's entries of
    // the loose ones are stale), and against those of the loose ones as they are now; a pair of
    // two refitted bodies once, from the lower.
    scan_.for_each_held(fat_[i], [&](std::uint32_t j) {
      if (!loose_[j]) add(i, j);
    });
    for (const std::uint32_t l : loose_list_) {
      if (l == i || !filed_placed_[l] || (refitting_[l] && l < i)) continue;
      if (CellTable::touch(fat_[i], fat_[l])) add(i, l);
    }
  }
  for (const std::uint32_t i : refit_)
    refitting_[i] = 0;
}

void PairCache::file(const BodyState& before, const BodyState& after) {
  for (std::size_t i = 0; i < box_.size(); ++i) {
    if (placed_[i]) fat_[i] = fatten(i, before, after);
  }
  filed_placed_ = placed_;
  scan_.build(fat_, placed_);
  pairs_.clear();
  scan_.for_each_pair_in_grid([&](std::uint32_t i, std::uint32_t j) { pairs_.emplace_back(i, j); });
  for (const std::uint32_t g : giants_)
    giant_[g] = 0;
  giants_.assign(scan_.giants().begin(), scan_.giants().end());
  for (const std::uint32_t g : giants_)
    giant_[g] = 1;
  adj_start_.assign(box_.size() + 1, 0);
  for (const auto& [i, j] : pairs_)
    ++adj_start_[i + 1], ++adj_start_[j + 1];
  for (std::size_t i = 1; i < adj_start_.size(); ++i)
    adj_start_[i] += adj_start_[i - 1];
  adj_.resize(2 * pairs_.size());
  for (const auto& [i, j] : pairs_)  // adj_start_[b] is b's fill cursor, shifted back below
    adj_[adj_start_[i]++] = j, adj_[adj_start_[j]++] = i;
  for (std::size_t i = adj_start_.size() - 1; i > 0; --i)
    adj_start_[i] = adj_start_[i - 1];
  adj_start_[0] = 0;
  for (const std::uint32_t l : loose_list_)
    loose_[l] = 0;
  loose_list_.clear();
  loose_pairs_.clear();
  filed_ = true;
  ++filings_;
}

}  // namespace chainbench
