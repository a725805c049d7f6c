// Broadphase: a uniform grid over body centres, rebuilt by a counting sort at every sweep.
//
// Cells are twice the 90th-percentile half extent of the movable bodies, so a body that fits a
// cell meets only bodies in the 3x3 cells around its own. Bodies too big for a cell (ground,
// walls, a giant box) are kept in a short list that every query includes. Cells are numbered
// row by row over the bounding box of the centres: when that box has fewer cells than the table
// has buckets, bucket = cell (no collisions) and a 3-cell row of a query is one contiguous run of
// entries; otherwise rows wrap around the table like a hash, and entries are filtered by cell.
//
// Bodies pushed after build() stay where they were bucketed; note_move() widens later queries by
// the largest such displacement, so a pair created by a push is never missed.
#pragma once

#include "bodies.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace chain::detail {

class Broadphase {
 public:
  // Chooses cells and the list of oversized bodies; call whenever the body set changes.
  void configure(const Bodies& bodies);
  // Buckets every body at its current position.
  void build(const Bodies& bodies);
  void note_move(std::uint32_t body, double x, double y) {
    margin_ =
        std::max(margin_, std::max(std::abs(x - build_x_[body]), std::abs(y - build_y_[body])));
  }

  // fn(i, j) with i < j, once for every pair whose boxes overlap by more than `tolerance` on
  // both axes at build time, except pairs of two immovable bodies. Call right after build().
  template <class Fn>
  void for_each_overlapping_pair(const Bodies& bodies, double tolerance, Fn&& fn) const;

  // fn(j) once for every body that may overlap the box at current positions (a superset: the
  // caller tests). Order depends only on positions and solve order.
  template <class Fn>
  void for_each_candidate(double min_x, double min_y, double max_x, double max_y, Fn&& fn) const;

  // fn(j) for the bodies near `body` as the grid saw them at build time, ignoring every move
  // since: the 2014 engine's grid, built once per frame and never updated.
  template <class Fn>
  void for_each_stale_candidate(const Bodies& bodies, std::uint32_t body, Fn&& fn) const;

  double cell_size() const { return cell_; }

 private:
  struct Entry {
    std::uint32_t body;
    std::int32_t cx, cy;
    std::uint32_t immovable;
    double min_x, min_y, max_x, max_y;
  };
  struct CellRange {
    std::int32_t x0, y0, x1, y1;
  };

  // Queries covering more cells than this scan every entry instead.
  static constexpr std::int64_t kMaxScanCells = 4096;

  std::int32_t cell_x(double x) const { return clamp_cell((x - origin_x_) * inv_cell_, width_); }
  std::int32_t cell_y(double y) const { return clamp_cell((y - origin_y_) * inv_cell_, height_); }
  static std::int32_t clamp_cell(double c, std::uint32_t count) {
    if (!(c >= 0.0)) return 0;
    if (c >= static_cast<double>(count - 1)) return static_cast<std::int32_t>(count - 1);
    return static_cast<std::int32_t>(c);
  }
  std::uint32_t bucket(std::int32_t cx, std::int32_t cy) const {
    return (static_cast<std::uint32_t>(cy) * width_ + static_cast<std::uint32_t>(cx)) & mask_;
  }
  CellRange cells_of(double min_x, double min_y, double max_x, double max_y) const {
    return {cell_x(min_x), cell_y(min_y), cell_x(max_x), cell_y(max_y)};
  }
  template <class Fn>
  void scan(CellRange r, Fn&& fn) const;

  double cell_ = 1.0;
  double inv_cell_ = 1.0;
  double small_half_ = 0.0;  // largest half extent of a gridded body
  double margin_ = 0.0;      // largest displacement since build()
  double origin_x_ = 0.0;
  double origin_y_ = 0.0;
  std::uint32_t width_ = 1;
  std::uint32_t height_ = 1;
  std::uint32_t mask_ = 63;
  std::vector<std::uint32_t> grid_bodies_;  // slots kept in the grid, in solve order
  std::vector<std::uint32_t> large_;        // slots too big for a cell, in solve order
  std::vector<std::uint32_t> cell_start_;   // bucket -> first entry, size mask_ + 2
  std::vector<std::uint32_t> cursor_;
  std::vector<std::uint32_t> keys_;
  std::vector<std::int32_t> key_x_, key_y_;
  std::vector<Entry> entries_;  // grid bodies, grouped by bucket, solve order within a bucket
  std::vector<double> build_x_, build_y_;
};

template <class Fn>
void Broadphase::scan(CellRange r, Fn&& fn) const {
  if (static_cast<std::int64_t>(r.x1 - r.x0 + 1) * (r.y1 - r.y0 + 1) > kMaxScanCells) {
    for (const Entry& e : entries_) {
      if (e.cx >= r.x0 && e.cx <= r.x1 && e.cy >= r.y0 && e.cy <= r.y1) fn(e);
    }
    return;
  }
  for (std::int32_t cy = r.y0; cy <= r.y1; ++cy) {
    const std::uint32_t b0 = bucket(r.x0, cy);
    const std::uint32_t b1 = bucket(r.x1, cy);
    if (b1 >= b0 && b1 - b0 == static_cast<std::uint32_t>(r.x1 - r.x0)) {
      // The row's buckets are contiguous: one run of entries.
      for (std::uint32_t k = cell_start_[b0], end = cell_start_[b1 + 1]; k < end; ++k) {
        const Entry& e = entries_[k];
        if (e.cy == cy && e.cx >= r.x0 && e.cx <= r.x1) fn(e);
      }
      continue;
    }
    for (std::int32_t cx = r.x0; cx <= r.x1; ++cx) {
      const std::uint32_t b = bucket(cx, cy);
      for (std::uint32_t k = cell_start_[b], end = cell_start_[b + 1]; k < end; ++k) {
        const Entry& e = entries_[k];
        if (e.cx == cx && e.cy == cy) fn(e);
      }
    }
  }
}

template <class Fn>
void Broadphase::for_each_overlapping_pair(const Bodies& bodies, double tolerance, Fn&& fn) const {
  auto overlaps = [tolerance](double ax0, double ay0, double ax1, double ay1, const Entry& f) {
    return std::min(ax1, f.max_x) - std::max(ax0, f.min_x) > tolerance &&
           std::min(ay1, f.max_y) - std::max(ay0, f.min_y) > tolerance;
  };
  const auto last_x = static_cast<std::int32_t>(width_ - 1);
  const auto last_y = static_cast<std::int32_t>(height_ - 1);
  for (const Entry& e : entries_) {
    const CellRange r{std::max(e.cx - 1, 0), std::max(e.cy - 1, 0), std::min(e.cx + 1, last_x),
                      std::min(e.cy + 1, last_y)};
    scan(r, [&](const Entry& f) {
      if (f.body <= e.body || (e.immovable & f.immovable)) return;
      if (overlaps(e.min_x, e.min_y, e.max_x, e.max_y, f)) fn(e.body, f.body);
    });
  }
  for (std::size_t k = 0; k < large_.size(); ++k) {
    const std::uint32_t l = large_[k];
    const bool l_immovable = bodies.immovable(l);
    const double x0 = bodies.x[l] - bodies.hx[l], x1 = bodies.x[l] + bodies.hx[l];
    const double y0 = bodies.y[l] - bodies.hy[l], y1 = bodies.y[l] + bodies.hy[l];
    scan(cells_of(x0 - small_half_, y0 - small_half_, x1 + small_half_, y1 + small_half_),
         [&](const Entry& f) {
           if (l_immovable && f.immovable) return;
           if (overlaps(x0, y0, x1, y1, f)) fn(std::min(l, f.body), std::max(l, f.body));
         });
    for (std::size_t m = k + 1; m < large_.size(); ++m) {
      const std::uint32_t o = large_[m];
      if (l_immovable && bodies.immovable(o)) continue;
      const Entry f{o,
                    0,
                    0,
                    0,
                    bodies.x[o] - bodies.hx[o],
                    bodies.y[o] - bodies.hy[o],
                    bodies.x[o] + bodies.hx[o],
                    bodies.y[o] + bodies.hy[o]};
      if (overlaps(x0, y0, x1, y1, f)) fn(std::min(l, o), std::max(l, o));
    }
  }
}

template <class Fn>
void Broadphase::for_each_candidate(double min_x, double min_y, double max_x, double max_y,
                                    Fn&& fn) const {
  const double pad = small_half_ + margin_;
  scan(cells_of(min_x - pad, min_y - pad, max_x + pad, max_y + pad),
       [&](const Entry& e) { fn(e.body); });
  for (const std::uint32_t l : large_)
    fn(l);
}

template <class Fn>
void Broadphase::for_each_stale_candidate(const Bodies& bodies, std::uint32_t body, Fn&& fn) const {
  const double hx = bodies.hx[body] + small_half_, hy = bodies.hy[body] + small_half_;
  const double x = build_x_[body], y = build_y_[body];
  scan(cells_of(x - hx, y - hy, x + hx, y + hy), [&](const Entry& e) { fn(e.body); });
  for (const std::uint32_t l : large_)
    fn(l);
}

}  // namespace chain::detail
