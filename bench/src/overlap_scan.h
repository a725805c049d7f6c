// Measures overlap between the scene's declared boxes from positions (and angles) alone, never
// from what an engine reports. A uniform grid over the centres finds candidate pairs; pairs of
// two non-dynamic bodies are ignored (a scene may build walls into its floor).
#pragma once

#include "engine.h"
#include "scene.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

namespace chainbench {

class OverlapScan {
 public:
  explicit OverlapScan(const Scene& scene);
  // The deepest overlap (depth along the axis of least penetration) between any two boxes. If
  // `per_body` is not empty it receives each body's own deepest overlap.
  double deepest(const BodyState& state, std::span<double> per_body);

 private:
  double depth(const BodyState& s, std::size_t i, std::size_t j) const {
    if (!rotated_) return aligned_depth(s.position[i], s.position[j], half_[i], half_[j]);
    return turned_depth(s, i, j);
  }
  static double aligned_depth(Vec2d a, Vec2d b, Vec2d ha, Vec2d hb) {
    const double ox = ha.x + hb.x - std::abs(a.x - b.x);
    const double oy = ha.y + hb.y - std::abs(a.y - b.y);
    return (ox > 0.0 && oy > 0.0) ? std::min(ox, oy) : 0.0;
  }
  double turned_depth(const BodyState& s, std::size_t i, std::size_t j) const;
  std::uint64_t bucket(std::int64_t cx, std::int64_t cy) const;

  std::vector<Vec2d> half_;
  std::vector<std::uint8_t> dynamic_;
  std::vector<std::uint8_t> large_flag_;
  std::vector<std::size_t> large_;  // bodies bigger than a cell: tested against all others
  std::vector<std::size_t> small_;
  double cell_ = 1.0;
  std::uint64_t mask_ = 0;
  bool rotated_ = false;
  std::vector<std::uint32_t> start_, order_;
  std::vector<std::uint64_t> key_;
  std::vector<std::int64_t> cx_, cy_;
};

}  // namespace chainbench
