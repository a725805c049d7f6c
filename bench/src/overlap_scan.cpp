#include "overlap_scan.h"

#include <algorithm>
#include <bit>
#include <cmath>

namespace chainbench {

OverlapScan::OverlapScan(const Scene& scene) : rotated_(scene.rotation) {
  const std::size_t n = scene.bodies.size();
  std::vector<double> sizes;
  for (const SceneBody& b : scene.bodies) {
    // With rotation a box reaches as far as its half diagonal, whatever its angle.
    const double r = rotated_ ? std::hypot(b.half_extents.x, b.half_extents.y)
                              : std::max(b.half_extents.x, b.half_extents.y);
    half_.push_back(b.half_extents);
    dynamic_.push_back(b.kind == BodyKind::kDynamic);
    if (b.kind == BodyKind::kDynamic) sizes.push_back(r);
  }
  if (!sizes.empty()) {
    const auto k = static_cast<std::ptrdiff_t>((sizes.size() - 1) * 9 / 10);
    std::nth_element(sizes.begin(), sizes.begin() + k, sizes.end());
    cell_ = std::max(2.0 * sizes[static_cast<std::size_t>(k)], 1e-9);
  }
  large_flag_.assign(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const double r =
        rotated_ ? std::hypot(half_[i].x, half_[i].y) : std::max(half_[i].x, half_[i].y);
    (r <= 0.5 * cell_ ? small_ : large_).push_back(i);
    large_flag_[i] = r > 0.5 * cell_;
  }
  const std::uint64_t table = std::bit_ceil(std::max<std::uint64_t>(64, 2 * small_.size()));
  mask_ = table - 1;
  start_.assign(table + 1, 0);
  order_.resize(small_.size());
  key_.resize(small_.size());
  cx_.resize(n);
  cy_.resize(n);
}

std::uint64_t OverlapScan::bucket(std::int64_t cx, std::int64_t cy) const {
  const auto h = static_cast<std::uint64_t>(cx) * 0x9E3779B97F4A7C15ull ^
                 static_cast<std::uint64_t>(cy) * 0xC2B2AE3D27D4EB4Full;
  return (h ^ (h >> 29)) & mask_;
}

double OverlapScan::turned_depth(const BodyState& s, std::size_t i, std::size_t j) const {
  const Vec2d a = s.position[i], b = s.position[j];
  if (s.angle[i] == 0.0 && s.angle[j] == 0.0) return aligned_depth(a, b, half_[i], half_[j]);
  // Separating axes of two turned boxes: each box's two edge normals.
  const double d[2] = {b.x - a.x, b.y - a.y};
  const double axes[4][2] = {{std::cos(s.angle[i]), std::sin(s.angle[i])},
                             {-std::sin(s.angle[i]), std::cos(s.angle[i])},
                             {std::cos(s.angle[j]), std::sin(s.angle[j])},
                             {-std::sin(s.angle[j]), std::cos(s.angle[j])}};
  auto reach = [&](std::size_t k, const double* axis) {
    const double c = std::cos(s.angle[k]), sn = std::sin(s.angle[k]);
    return half_[k].x * std::abs(axis[0] * c + axis[1] * sn) +
           half_[k].y * std::abs(-axis[0] * sn + axis[1] * c);
  };
  double least = 1e300;
  for (const auto& axis : axes) {
    const double overlap =
        reach(i, axis) + reach(j, axis) - std::abs(d[0] * axis[0] + d[1] * axis[1]);
    if (overlap <= 0.0) return 0.0;
    least = std::min(least, overlap);
  }
  return least;
}

double OverlapScan::deepest(const BodyState& s, std::span<double> per_body) {
  std::fill(per_body.begin(), per_body.end(), 0.0);
  double worst = 0.0;
  auto consider = [&](std::size_t i, std::size_t j) {
    if (!dynamic_[i] && !dynamic_[j]) return;
    const double d = depth(s, i, j);
    if (d <= 0.0) return;
    worst = std::max(worst, d);
    if (!per_body.empty()) {
      per_body[i] = std::max(per_body[i], d);
      per_body[j] = std::max(per_body[j], d);
    }
  };
  auto cell = [&](double v) {
    const double c = std::floor(v / cell_);
    return static_cast<std::int64_t>(std::clamp(c, -4.0e18, 4.0e18));
  };
  // Counting sort of the small bodies into buckets.
  std::fill(start_.begin(), start_.end(), 0u);
  for (std::size_t k = 0; k < small_.size(); ++k) {
    const std::size_t i = small_[k];
    if (!std::isfinite(s.position[i].x) || !std::isfinite(s.position[i].y)) {
      cx_[i] = cy_[i] = 0;  // a lost body still gets a place; its depth test fails anyway
    } else {
      cx_[i] = cell(s.position[i].x);
      cy_[i] = cell(s.position[i].y);
    }
    key_[k] = bucket(cx_[i], cy_[i]);
    ++start_[key_[k] + 1];
  }
  for (std::size_t b = 1; b < start_.size(); ++b)
    start_[b] += start_[b - 1];
  for (std::size_t k = 0; k < small_.size(); ++k)
    order_[start_[key_[k]]++] = static_cast<std::uint32_t>(small_[k]);
  for (std::size_t b = start_.size() - 1; b > 0; --b)
    start_[b] = start_[b - 1];
  start_[0] = 0;

  // The forward half of each body's 3x3 neighbourhood: every pair of small bodies once.
  constexpr std::int64_t kForward[5][2] = {{0, 0}, {1, 0}, {-1, 1}, {0, 1}, {1, 1}};
  for (const std::size_t i : small_) {
    for (const auto& d : kForward) {
      const std::int64_t nx = cx_[i] + d[0], ny = cy_[i] + d[1];
      const std::uint64_t b = bucket(nx, ny);
      for (std::uint32_t k = start_[b]; k < start_[b + 1]; ++k) {
        const std::size_t j = order_[k];
        if (cx_[j] != nx || cy_[j] != ny || (d[0] == 0 && d[1] == 0 && j <= i)) continue;
        consider(i, j);
      }
    }
  }
  for (const std::size_t l : large_) {
    for (std::size_t j = 0; j < half_.size(); ++j) {
      if (j == l || (large_flag_[j] && j < l)) continue;  // each large pair once
      consider(std::min(l, j), std::max(l, j));
    }
  }
  return worst;
}

}  // namespace chainbench
