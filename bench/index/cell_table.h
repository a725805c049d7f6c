// SPDX-License-Identifier: MIT
// The hashed uniform grid shared by BoxGrid and PairScan: boxes held in every cell they cover, and
// the walks that find which held boxes touch a query box, or each other, each pair once.
//
// Where the occupied cells span a range no bigger than a few times the entries, each cell of that
// range is a bucket of its own, row by row, so that neighbouring buckets hold neighbouring boxes.
// Otherwise (a few bodies flung far away) cells are hashed into a power-of-two table of buckets,
// so the grid is unbounded and costs memory for the occupied cells only; entries of other cells
// that share a bucket are skipped. Each entry keeps a copy of its box, in bucket order, so that
// a walk reads the boxes it tests front to back. A pair met in several cells is reported by the
// one cell holding the lower-left corner of the two boxes' intersection, so once, without a set
// of pairs already seen.
//
// The table owns its buffers and refills them in place: once warmed up to a scene's size, a
// rebuild allocates nothing (PairScan rebuilds at every filing of a PairCache).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

namespace chainbench {

class CellTable {
 public:
  struct Box {
    double x0, y0, x1, y1;
  };
  // The cells a box covers, inclusive.
  struct Cells {
    std::int64_t x0, y0, x1, y1;
    // In double: a box of a huge world can span more cells than an int64 holds.
    double count() const {
      return (static_cast<double>(x1) - static_cast<double>(x0) + 1.0) *
             (static_cast<double>(y1) - static_cast<double>(y0) + 1.0);
    }
  };
  // A box covering more cells than this is better tested against every box than entered in each.
  static constexpr double kMaxCells = 1024;

  explicit CellTable(double cell = 1.0) : inv_cell_(1.0 / std::max(cell, 1e-9)) {}

  static bool touch(const Box& a, const Box& b) {
    return a.x0 <= b.x1 && b.x0 <= a.x1 && a.y0 <= b.y1 && b.y0 <= a.y1;
  }
  // Clamped so that a far or huge box still maps to a cell instead of overflowing.
  std::int64_t cell(double v) const {
    return static_cast<std::int64_t>(std::floor(std::clamp(v * inv_cell_, -4.0e18, 4.0e18)));
  }
  Cells cover(const Box& b) const { return {cell(b.x0), cell(b.y0), cell(b.x1), cell(b.y1)}; }

  // Building: clear(), add() every box to hold, then sort(boxes) with `boxes[k]` the box held as
  // k; until the next clear() the walks below see those boxes.
  void clear() { entries_.clear(); }
  // Holds box `index` in each of the cells `c` (from cover(); keep their count small).
  void add(std::uint32_t index, const Cells& c) {
    for (std::int64_t cy = c.y0; cy <= c.y1; ++cy) {
      for (std::int64_t cx = c.x0; cx <= c.x1; ++cx)
        entries_.push_back({index, corner_flags(c, cx, cy), cx, cy});
    }
  }
  void sort(std::span<const Box> boxes);

  // fn(k) once for every held box k that touches `q` (covering the cells `c`, from cover(q)). In
  // order of the cells (row by row), then of addition.
  template <class Fn>
  void for_each_in_cells(const Box& q, Cells c, Fn&& fn) const;
  // fn(k, m) once for every two held boxes that touch, k added before m in a shared cell. Bucket by
  // bucket, then in order of addition.
  template <class Fn>
  void for_each_pair(Fn&& fn) const;

 private:
  // Of a box covering the cells `c`, where cell (cx, cy) lies: kFirstColumn when in the first
  // column it covers, kFirstRow in the first row.
  static constexpr std::uint8_t kFirstColumn = 1, kFirstRow = 2;
  static std::uint8_t corner_flags(const Cells& c, std::int64_t cx, std::int64_t cy) {
    return static_cast<std::uint8_t>((cx == c.x0 ? kFirstColumn : 0) |
                                     (cy == c.y0 ? kFirstRow : 0));
  }
  struct Entry {
    std::uint32_t index;
    std::uint8_t corner;  // corner_flags() of its box and cell
    std::int64_t cx, cy;
  };
  std::uint64_t bucket(std::int64_t cx, std::int64_t cy) const {
    if (dense_) {
      return static_cast<std::uint64_t>(cy - range_.y0) * static_cast<std::uint64_t>(width_) +
             static_cast<std::uint64_t>(cx - range_.x0);
    }
    const auto h = static_cast<std::uint64_t>(cx) * 0x9E3779B97F4A7C15ull ^
                   static_cast<std::uint64_t>(cy) * 0xC2B2AE3D27D4EB4Full;
    return (h ^ (h >> 29)) & mask_;
  }
  // Whether a cell both boxes cover holds the lower-left corner of their intersection, the one
  // cell of those they share that reports them, from their corner_flags() there: cell() does not
  // decrease, so the corner's column, cell(max(a.x0, b.x0)), is the later of the two boxes' first
  // columns, and it is this cell's when either box's first column is; rows likewise.
  static bool reports(std::uint8_t a, std::uint8_t b) {
    return ((a | b) & (kFirstColumn | kFirstRow)) == (kFirstColumn | kFirstRow);
  }

  double inv_cell_;
  std::vector<Entry> entries_;        // as added
  std::vector<Entry> sorted_;         // by bucket
  std::vector<Box> sorted_box_;       // the box of each entry of sorted_
  std::vector<std::uint32_t> start_;  // per bucket, into sorted_
  std::uint64_t mask_ = 0;            // hashed buckets
  bool dense_ = false;                // a bucket per cell of range_
  Cells range_{};                     // of the occupied cells (dense_)
  std::int64_t width_ = 0;            // cells per row of range_
};

template <class Fn>
void CellTable::for_each_in_cells(const Box& q, Cells c, Fn&& fn) const {
  if (sorted_.empty()) return;
  const Cells covered = c;  // q's own first column and row, before the clamp below
  if (dense_) {             // no cell outside the range holds anything
    c = {std::max(c.x0, range_.x0), std::max(c.y0, range_.y0), std::min(c.x1, range_.x1),
         std::min(c.y1, range_.y1)};
  }
  for (std::int64_t cy = c.y0; cy <= c.y1; ++cy) {
    for (std::int64_t cx = c.x0; cx <= c.x1; ++cx) {
      const std::uint64_t b = bucket(cx, cy);
      const std::uint8_t corner = corner_flags(covered, cx, cy);
      for (std::uint32_t k = start_[b]; k < start_[b + 1]; ++k) {
        const Entry& e = sorted_[k];
        if (e.cx != cx || e.cy != cy) continue;  // another cell in the same bucket
        if (touch(q, sorted_box_[k]) && reports(e.corner, corner)) fn(e.index);
      }
    }
  }
}

template <class Fn>
void CellTable::for_each_pair(Fn&& fn) const {
  // Walking the entries rather than the (mostly empty) table of buckets.
  for (std::uint32_t first = 0, last = 0; first < sorted_.size(); first = last) {
    last = start_[bucket(sorted_[first].cx, sorted_[first].cy) + 1];
    for (std::uint32_t k = first; k < last; ++k) {
      const Entry& e = sorted_[k];
      const Box& a = sorted_box_[k];
      for (std::uint32_t m = k + 1; m < last; ++m) {
        const Entry& f = sorted_[m];
        if (f.cx != e.cx || f.cy != e.cy || f.index == e.index) continue;
        if (touch(a, sorted_box_[m]) && reports(e.corner, f.corner)) fn(e.index, f.index);
      }
    }
  }
}

}  // namespace chainbench
