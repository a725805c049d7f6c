// SPDX-License-Identifier: MIT
#include "index/pair_scan.h"

#include <algorithm>

namespace chainbench {

PairScan::PairScan(const Scene& scene, double scale) : rotated_(scene.rotation) {
  const std::size_t n = scene.bodies.size();
  std::vector<double> sizes;
  for (const SceneBody& b : scene.bodies) {
    half_.push_back(b.half_extents);
    // A turned box reaches as far as its half diagonal on either axis.
    const double diagonal = std::hypot(b.half_extents.x, b.half_extents.y);
    reach_.push_back(rotated_ ? Vec2d{diagonal, diagonal} : b.half_extents);
    dynamic_.push_back(b.kind == BodyKind::kDynamic);
    if (b.kind == BodyKind::kDynamic) sizes.push_back(std::max(reach_.back().x, reach_.back().y));
  }
  double cell = 1.0;
  if (!sizes.empty()) {
    // Most dynamic boxes fit a cell; the few bigger ones cover a few cells each.
    const auto k = static_cast<std::ptrdiff_t>((sizes.size() - 1) * 9 / 10);
    std::nth_element(sizes.begin(), sizes.begin() + k, sizes.end());
    cell = std::max(2.0 * scale * sizes[static_cast<std::size_t>(k)], 1e-9);
  }
  cell_ = cell;
  table_ = CellTable(cell);
  swept_.resize(n);
  live_.assign(n, 0);
  giant_.assign(n, 0);
}

bool PairScan::swept(std::size_t i, const BodyState& before, const BodyState& after,
                     Box& out) const {
  const Vec2d p = before.position[i], q = after.position[i];
  if (!(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(q.x) && std::isfinite(q.y)))
    return false;
  const Vec2d r = reach_[i];
  out = {std::min(p.x, q.x) - r.x, std::min(p.y, q.y) - r.y, std::max(p.x, q.x) + r.x,
         std::max(p.y, q.y) + r.y};
  return true;
}

void PairScan::add(std::size_t i, const BodyState& before, const BodyState& after) {
  Box box;
  live_[i] = swept(i, before, after, box);
  giant_[i] = 0;
  if (live_[i]) file(i, box);
}

void PairScan::file(std::size_t i, const Box& box) {
  swept_[i] = box;
  const CellTable::Cells c = table_.cover(box);
  if (c.count() > CellTable::kMaxCells) {
    giant_[i] = 1;
    giants_.push_back(static_cast<std::uint32_t>(i));
    return;
  }
  table_.add(static_cast<std::uint32_t>(i), c);
}

void PairScan::build(const BodyState& before, const BodyState& after) {
  table_.clear();
  giants_.clear();
  for (std::size_t i = 0; i < half_.size(); ++i)
    add(i, before, after);
  table_.sort(swept_);
}

void PairScan::build(std::span<const Box> boxes, std::span<const std::uint8_t> live) {
  table_.clear();
  giants_.clear();
  for (std::size_t i = 0; i < half_.size(); ++i) {
    live_[i] = live[i];
    giant_[i] = 0;
    if (live_[i]) file(i, boxes[i]);
  }
  table_.sort(swept_);
}

double PairScan::depth(const BodyState& s, std::size_t i, std::size_t j) const {
  const Vec2d a = s.position[i], b = s.position[j];
  if (!rotated_ || (s.angle[i] == 0.0 && s.angle[j] == 0.0)) {
    const double ox = half_[i].x + half_[j].x - std::abs(a.x - b.x);
    const double oy = half_[i].y + half_[j].y - std::abs(a.y - b.y);
    return (ox > 0.0 && oy > 0.0) ? std::min(ox, oy) : 0.0;
  }
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

}  // namespace chainbench
