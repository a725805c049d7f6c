// Broadphase: uniform grids over body centres, one per size class, rebuilt by a counting sort at
// every sweep.
//
// Bodies are split into levels by size: a level takes every remaining body up to 4 times the
// median size of the remaining movable bodies, and its cells are 2 * (its largest half extent)
// + slack wide, so a body meets only bodies in the 3x3 cells around its own, even slack apart.
// A pyramid is one level of boxes and one of a single ground box; a pile of mixed sizes is one
// level; a scene of pebbles and boulders is two. Cells are numbered row by row over the bounding
// box of a level's centres: when that box has no more cells than the table has buckets, bucket =
// cell and a 3-cell row of a query is one contiguous run of entries; otherwise rows wrap around
// the table like a hash, and entries are filtered by cell.
//
// A body moved after build() stays in the bucket and entry it was built into: note_move() widens
// later queries by the largest displacement so far, and queries test current positions from
// the bodies, so a pair created by a push is never missed. Integration notes its moves too, so
// telling whether the near pairs still hold needs no pass over the bodies.
#pragma once

#include "bodies.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

namespace chain::detail {

class Broadphase {
 public:
  // Chooses levels and cells; call whenever the body set changes.
  void configure(const Bodies& bodies);
  // The slots were renumbered (slot i was order[i]): files each body under its new slot. Like
  // configure(), it changes generation(), and the next query needs build().
  void renumber(std::span<const std::uint32_t> order);
  // Buckets every body at its current position.
  void build(const Bodies& bodies);
  // Changes whenever the body set changes (configure()) or the slots are renumbered.
  std::uint64_t generation() const { return generation_; }
  // Every move of a body after build() must be noted, integration included: queries and
  // near_pairs_hold() go by the largest displacement since build().
  void note_move(std::uint32_t body, double x, double y) {
    margin_ = std::max(margin_,
                       std::max(std::abs(x - built_at_[body].x), std::abs(y - built_at_[body].y)));
  }
  // True while no body has moved a quarter of the slack since build(): every pair that can
  // overlap now was a near pair then.
  bool near_pairs_hold() const { return 4.0 * margin_ < slack_; }
  // Pairs closer than this are near pairs.
  double slack() const { return slack_; }
  // The largest displacement of any body from where build() saw it, at any move since.
  double moved() const { return margin_; }

  // fn(i, j) with i < j, once for every pair whose boxes are less than slack() apart on both
  // axes at build time, except pairs of two immovable bodies. Call right after build().
  template <class Fn>
  void for_each_near_pair(Fn&& fn) const;

  // fn(j) once for every body j != body whose box now overlaps body's box by more than
  // `tolerance` on both axes. Order depends only on positions and solve order.
  template <class Fn>
  void for_each_overlap(const Bodies& bodies, std::uint32_t body, double tolerance, Fn&& fn) const;

  // fn(j) once for every body whose box now comes within `slack` of the box (x +- hx, y +- hy)
  // on both axes (slack 0: touching counts). Order depends only on positions and solve order.
  template <class Fn>
  void for_each_in_box(const Bodies& bodies, double x, double y, double hx, double hy, double slack,
                       Fn&& fn) const;

  // fn(j) for the bodies near `body` as the grid saw them at build time, ignoring every move
  // since: the 2014 engine's grid, built once per frame and never updated.
  template <class Fn>
  void for_each_stale_candidate(const Bodies& bodies, std::uint32_t body, Fn&& fn) const;

  std::size_t level_count() const { return levels_.size(); }

 private:
  struct Entry {  // a body: the cell it was built into, and its box then
    std::uint32_t body;
    std::int32_t cx, cy;
    std::uint32_t immovable;
    double x, y, hx, hy;
  };
  struct CellRange {
    std::int32_t x0, y0, x1, y1;
  };
  // Queries covering more cells than this scan every entry of the level instead.
  static constexpr std::int64_t kMaxScanCells = 4096;

  struct Level {
    double cell = 1.0, inv_cell = 1.0;
    double small_half = 0.0;  // largest half extent in the level
    double origin_x = 0.0, origin_y = 0.0;
    std::uint32_t width = 1, height = 1, mask = 63;
    bool dense = true;                  // every cell has a bucket of its own
    std::vector<std::uint32_t> bodies;  // slots, in solve order
    std::vector<std::uint32_t> cell_start, cursor, keys;
    std::vector<std::int32_t> key_x, key_y;
    std::vector<Entry> entries;  // grouped by bucket, solve order within a bucket

    std::int32_t cell_x(double x) const { return clamp_cell((x - origin_x) * inv_cell, width); }
    std::int32_t cell_y(double y) const { return clamp_cell((y - origin_y) * inv_cell, height); }
    std::uint32_t bucket(std::int32_t cx, std::int32_t cy) const {
      return (static_cast<std::uint32_t>(cy) * width + static_cast<std::uint32_t>(cx)) & mask;
    }
    // The cells whose bodies may reach the box (x +- hx, y +- hy) grown by pad.
    CellRange cells_near(double x, double y, double hx, double hy, double pad) const {
      const double rx = hx + small_half + pad, ry = hy + small_half + pad;
      return {cell_x(x - rx), cell_y(y - ry), cell_x(x + rx), cell_y(y + ry)};
    }
    void build(const Bodies& bodies, std::vector<std::uint32_t>& entry_of);
    template <class Fn>
    void scan(CellRange r, Fn&& fn) const;
  };

  static std::int32_t clamp_cell(double c, std::uint32_t count) {
    if (!(c >= 0.0)) return 0;
    if (c >= static_cast<double>(count - 1)) return static_cast<std::int32_t>(count - 1);
    return static_cast<std::int32_t>(c);
  }
  static bool within(double x, double y, double hx, double hy, const Entry& e, double gap) {
    return (hx + e.hx) - std::abs(x - e.x) > gap && (hy + e.hy) - std::abs(y - e.y) > gap;
  }

  std::vector<Level> levels_;
  std::vector<std::uint8_t> level_of_;   // per slot
  std::vector<std::uint32_t> entry_of_;  // per slot: index in its level's entries
  struct Point {
    double x, y;
  };
  // Per slot, where build() saw the body: x and y together, as every note_move() reads both.
  std::vector<Point> built_at_;
  double margin_ = 0.0;
  double slack_ = 0.0;
  std::uint64_t generation_ = 0;
};

template <class Fn>
void Broadphase::Level::scan(CellRange r, Fn&& fn) const {
  if (static_cast<std::int64_t>(r.x1 - r.x0 + 1) * (r.y1 - r.y0 + 1) > kMaxScanCells) {
    for (const Entry& e : entries) {
      if (e.cx >= r.x0 && e.cx <= r.x1 && e.cy >= r.y0 && e.cy <= r.y1) fn(e);
    }
    return;
  }
  for (std::int32_t cy = r.y0; cy <= r.y1; ++cy) {
    const std::uint32_t b0 = bucket(r.x0, cy);
    const std::uint32_t b1 = bucket(r.x1, cy);
    if (b1 >= b0 && b1 - b0 == static_cast<std::uint32_t>(r.x1 - r.x0)) {
      // The row's buckets are contiguous: one run of entries, which in a dense level holds
      // exactly the cells asked for.
      const std::uint32_t begin = cell_start[b0], end = cell_start[b1 + 1];
      if (dense) {
        for (std::uint32_t k = begin; k < end; ++k)
          fn(entries[k]);
      } else {
        for (std::uint32_t k = begin; k < end; ++k) {
          const Entry& e = entries[k];
          if (e.cy == cy && e.cx >= r.x0 && e.cx <= r.x1) fn(e);
        }
      }
      continue;
    }
    for (std::int32_t cx = r.x0; cx <= r.x1; ++cx) {
      const std::uint32_t b = bucket(cx, cy);
      for (std::uint32_t k = cell_start[b], end = cell_start[b + 1]; k < end; ++k) {
        const Entry& e = entries[k];
        if (e.cx == cx && e.cy == cy) fn(e);
      }
    }
  }
}

template <class Fn>
void Broadphase::for_each_near_pair(Fn&& fn) const {
  const double gap = -slack_;
  auto test = [&](const Entry& e, const Entry& f) {
    if (!(e.immovable & f.immovable) && within(e.x, e.y, e.hx, e.hy, f, gap)) {
      fn(std::min(e.body, f.body), std::max(e.body, f.body));
    }
  };
  for (std::size_t l = 0; l < levels_.size(); ++l) {
    const Level& level = levels_[l];
    const auto last_x = static_cast<std::int32_t>(level.width - 1);
    const auto last_y = static_cast<std::int32_t>(level.height - 1);
    // Within the level, half the neighbourhood: the own row (each pair once, by slot) and the
    // row above; the row below finds e when it is that row's turn.
    for (const Entry& e : level.entries) {
      const CellRange r{std::max(e.cx - 1, 0), e.cy, std::min(e.cx + 1, last_x),
                        std::min(e.cy + 1, last_y)};
      level.scan(r, [&](const Entry& f) {
        if (f.cy != e.cy || f.body > e.body) test(e, f);
      });
    }
    // Against every coarser level, from whichever side has fewer bodies: a ground box scans the
    // boxes around it once rather than every box scanning for the ground.
    for (std::size_t m = l + 1; m < levels_.size(); ++m) {
      const Level& coarse = levels_[m];
      if (coarse.entries.size() < level.entries.size()) {
        for (const Entry& c : coarse.entries) {
          level.scan(level.cells_near(c.x, c.y, c.hx, c.hy, slack_),
                     [&](const Entry& f) { test(c, f); });
        }
      } else {
        for (const Entry& e : level.entries) {
          coarse.scan(coarse.cells_near(e.x, e.y, e.hx, e.hy, slack_),
                      [&](const Entry& f) { test(e, f); });
        }
      }
    }
  }
}

template <class Fn>
void Broadphase::for_each_overlap(const Bodies& bodies, std::uint32_t body, double tolerance,
                                  Fn&& fn) const {
  const double x = bodies.x(body), y = bodies.y(body), hx = bodies.hx(body), hy = bodies.hy(body);
  for (const Level& level : levels_) {
    level.scan(level.cells_near(x, y, hx, hy, margin_), [&](const Entry& e) {
      const std::uint32_t j = e.body;
      if (j != body && (hx + bodies.hx(j)) - std::abs(x - bodies.x(j)) > tolerance &&
          (hy + bodies.hy(j)) - std::abs(y - bodies.y(j)) > tolerance) {
        fn(j);
      }
    });
  }
}

template <class Fn>
void Broadphase::for_each_in_box(const Bodies& bodies, double x, double y, double hx, double hy,
                                 double slack, Fn&& fn) const {
  for (const Level& level : levels_) {
    level.scan(level.cells_near(x, y, hx, hy, margin_ + slack), [&](const Entry& e) {
      const std::uint32_t j = e.body;
      if ((hx + bodies.hx(j)) - std::abs(x - bodies.x(j)) >= -slack &&
          (hy + bodies.hy(j)) - std::abs(y - bodies.y(j)) >= -slack) {
        fn(j);
      }
    });
  }
}

template <class Fn>
void Broadphase::for_each_stale_candidate(const Bodies& bodies, std::uint32_t body, Fn&& fn) const {
  const double x = built_at_[body].x, y = built_at_[body].y, hx = bodies.hx(body),
               hy = bodies.hy(body);
  for (const Level& level : levels_) {
    level.scan(level.cells_near(x, y, hx, hy, 0.0), [&](const Entry& e) { fn(e.body); });
  }
}

}  // namespace chain::detail
