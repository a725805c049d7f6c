#include "pair_cache.h"

#include <cmath>

namespace chainbench {

PairCache::PairCache(const Scene& scene) : scan_(scene) {
  const std::size_t n = scene.bodies.size();
  box_.resize(n);
  fat_.resize(n);
  live_.assign(n, 0);
  placed_.assign(n, 0);
  filed_placed_.assign(n, 0);
}

bool PairCache::sweep(const BodyState& before, const BodyState& after) {
  bool all_fit = filed_;
  for (std::size_t i = 0; i < box_.size(); ++i)
    all_fit &= measure(i, before, after);
  return all_fit;
}

void PairCache::file(const BodyState& before, const BodyState& after) {
  // A quarter of a cell: a few more pairs on the list than touch, and a body that starts to move
  // stays filed for a few steps. The distance moved keeps a steady mover filed for about two
  // steps more than that.
  const double margin = 0.25 * scan_.cell();
  for (std::size_t i = 0; i < box_.size(); ++i) {
    if (!placed_[i]) continue;
    double gx = margin, gy = margin;
    if (live_[i]) {
      gx += 2.0 * std::abs(after.position[i].x - before.position[i].x);
      gy += 2.0 * std::abs(after.position[i].y - before.position[i].y);
    }
    const Box& s = box_[i];
    fat_[i] = {s.x0 - gx, s.y0 - gy, s.x1 + gx, s.y1 + gy};
  }
  filed_placed_ = placed_;
  scan_.build(fat_, placed_);
  pairs_.clear();
  scan_.for_each_pair([&](std::size_t i, std::size_t j) {
    pairs_.emplace_back(static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(j));
  });
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
  filed_ = true;
  ++filings_;
}

}  // namespace chainbench
