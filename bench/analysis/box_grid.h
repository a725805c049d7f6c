// A uniform grid over a fixed set of axis-aligned boxes, for finding every box that touches a
// query box in time proportional to the cells the query covers and the boxes in them, instead of
// to all the boxes: what keeps a query per cluster, body or pair linear in the scene.
//
// Each box is held in every cell it covers (cells are hashed into buckets); a box touching the
// query in several cells is reported by the one holding the lower-left corner of their
// intersection, so once. A box covering more than kMaxCells cells is tested against every query
// instead, and a query covering more cells than there are boxes tests every box.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

namespace chainbench {

class BoxGrid {
 public:
  struct Box {
    double x0, y0, x1, y1;
  };
  // `boxes` must be finite; `cell` is the cells' side (about the size of most boxes).
  BoxGrid(std::span<const Box> boxes, double cell);

  // fn(k) once for every box k (its index in `boxes`) that overlaps or touches `q`.
  template <class Fn>
  void for_each_touching(const Box& q, Fn&& fn) const;

 private:
  static constexpr std::int64_t kMaxCells = 1024;
  struct Entry {
    std::uint32_t box;
    std::int64_t cx, cy;
  };
  std::int64_t cell(double v) const {
    return static_cast<std::int64_t>(std::floor(std::clamp(v * inv_cell_, -4.0e18, 4.0e18)));
  }
  std::uint64_t bucket(std::int64_t cx, std::int64_t cy) const {
    const auto h = static_cast<std::uint64_t>(cx) * 0x9E3779B97F4A7C15ull ^
                   static_cast<std::uint64_t>(cy) * 0xC2B2AE3D27D4EB4Full;
    return (h ^ (h >> 29)) & mask_;
  }
  static bool touch(const Box& a, const Box& b) {
    return a.x0 <= b.x1 && b.x0 <= a.x1 && a.y0 <= b.y1 && b.y0 <= a.y1;
  }

  std::vector<Box> boxes_;
  double inv_cell_ = 1.0;
  std::vector<std::uint32_t> giants_;
  std::vector<Entry> sorted_;         // by bucket
  std::vector<std::uint32_t> start_;  // per bucket, into sorted_
  std::uint64_t mask_ = 0;
};

template <class Fn>
void BoxGrid::for_each_touching(const Box& q, Fn&& fn) const {
  const std::int64_t cx0 = cell(q.x0), cx1 = cell(q.x1), cy0 = cell(q.y0), cy1 = cell(q.y1);
  const double cells = (static_cast<double>(cx1) - static_cast<double>(cx0) + 1.0) *
                       (static_cast<double>(cy1) - static_cast<double>(cy0) + 1.0);
  if (cells > static_cast<double>(boxes_.size())) {  // walking every box is cheaper
    for (std::uint32_t k = 0; k < boxes_.size(); ++k) {
      if (touch(q, boxes_[k])) fn(static_cast<std::size_t>(k));
    }
    return;
  }
  for (std::int64_t cy = cy0; cy <= cy1; ++cy) {
    for (std::int64_t cx = cx0; cx <= cx1; ++cx) {
      const std::uint64_t b = bucket(cx, cy);
      for (std::uint32_t k = start_[b]; k < start_[b + 1]; ++k) {
        const Entry& e = sorted_[k];
        if (e.cx != cx || e.cy != cy) continue;
        const Box& a = boxes_[e.box];
        if (!touch(q, a)) continue;
        if (cell(std::max(a.x0, q.x0)) != cx || cell(std::max(a.y0, q.y0)) != cy) continue;
        fn(static_cast<std::size_t>(e.box));
      }
    }
  }
  for (const std::uint32_t g : giants_) {
    if (touch(q, boxes_[g])) fn(static_cast<std::size_t>(g));
  }
}

}  // namespace chainbench
