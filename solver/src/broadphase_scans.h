// SPDX-License-Identifier: MIT
// The templates of broadphase.h (which includes this file at its end): the scans of a level's
// grid and of the overlay, the near-pair scan, and the queries.
#pragma once

#include "broadphase.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace chain::detail {

template <class Fn>
void Broadphase::Level::scan(CellRange r, std::uint64_t& examined_total, Fn&& fn) const {
  // Counted locally: the total is a member that fn may be assumed to change.
  std::uint64_t examined = 0;
  struct Add {
    std::uint64_t& to;
    const std::uint64_t& count;
    ~Add() { to += count; }
  } add{examined_total, examined};
  if (static_cast<std::int64_t>(r.x1 - r.x0 + 1) * (r.y1 - r.y0 + 1) > kMaxScanCells) {
    examined += entries.size();
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
      examined += end - begin;
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
      examined += cell_start[b + 1] - cell_start[b];
      for (std::uint32_t k = cell_start[b], end = cell_start[b + 1]; k < end; ++k) {
        const Entry& e = entries[k];
        if (e.cx == cx && e.cy == cy) fn(e);
      }
    }
  }
}

template <class Fn>
void Broadphase::scan_overlay(std::size_t l, double x, double y, double rx, double ry,
                              Fn&& fn) const {
  const Level& level = levels_[l];
  // A level none of whose bodies was filed again has nothing in the overlay to find: the scan's
  // cell arithmetic and empty buckets would be all it did.
  if (level.overlay_members == 0) return;
  const std::int32_t x0 = level.overlay_x(x - rx), x1 = level.overlay_x(x + rx);
  const std::int32_t y0 = level.overlay_y(y - ry), y1 = level.overlay_y(y + ry);
  if ((static_cast<std::int64_t>(x1) - x0 + 1) * (static_cast<std::int64_t>(y1) - y0 + 1) >
      kMaxScanCells) {
    examined_ += members_.size();
    for (const std::uint32_t i : members_) {
      if (in_overlay_[i] && level_of_[i] == l && overlay_cx_[i] >= x0 && overlay_cx_[i] <= x1 &&
          overlay_cy_[i] >= y0 && overlay_cy_[i] <= y1) {
        fn(i);
      }
    }
    return;
  }
  for (std::int32_t cy = y0; cy <= y1; ++cy) {
    for (std::int32_t cx = x0; cx <= x1; ++cx) {
      for (std::uint32_t i = level.overlay_head[level.overlay_bucket(cx, cy)]; i != kNoSlot;
           i = next_[i]) {
        ++examined_;
        if (overlay_cx_[i] == cx && overlay_cy_[i] == cy) fn(i);
      }
    }
  }
}

template <class Fn>
void Broadphase::scan_all(double x, double y, double hx, double hy, double pad, Fn&& fn) const {
  for (std::size_t l = 0; l < levels_.size(); ++l) {
    const Level& level = levels_[l];
    level.scan(level.cells_near(x, y, hx, hy, pad), examined_, [&](const Entry& e) {
      if (!e.out) fn(e.body);
    });
    scan_overlay(l, x, y, hx + level.small_half + pad, hy + level.small_half + pad, fn);
  }
}

template <class Fn>
void Broadphase::for_each_near_pair(const Bodies& bodies, Fn&& fn) {
  // Overlay bodies are filed where they are now: their near pairs are found from there.
  next_scan();
  for (const std::uint32_t i : members_) {
    refile(i, bodies.x(i), bodies.y(i));
    epoch_of_[i] = scan_ + 1;
  }
  ++scan_;
  next_mark_epoch();
  unmarked_.clear();
  stale_ = 0;
  const double gap = -slack_;
  auto test = [&](const Entry& e, const Entry& f) {
    if (!((e.immovable & f.immovable) | e.out | f.out) && within(e.x, e.y, e.hx, e.hy, f, gap)) {
      fn(std::min(e.body, f.body), std::max(e.body, f.body));
    }
  };
  for (std::size_t l = 0; l < levels_.size(); ++l) {
    const Level& level = levels_[l];
    const auto last_x = static_cast<std::int32_t>(level.width - 1);
    const auto last_y = static_cast<std::int32_t>(level.height - 1);
    // Within the level, each pair once. Boxes no larger than the level's largest that are slack
    // apart have centres at most a cell apart, so in the next cells; with one of them stretched
    // (by at most that largest half extent), at most 2 cells apart. Two unstretched bodies are
    // found by half the neighbourhood of the next cells: the own row (by slot) and the row above,
    // the row below finding e when it is its turn. A pair with a stretched body is the stretched
    // body's to find: two cells all round for an unstretched partner, the own row and the two
    // above for a stretched one. Near lists are sorted (ChainState), so which side finds a pair
    // changes nothing.
    for (const Entry& e : level.entries) {
      if (e.out) continue;
      if (!e.stretched) {
        const CellRange r{std::max(e.cx - 1, 0), e.cy, std::min(e.cx + 1, last_x),
                          std::min(e.cy + 1, last_y)};
        level.scan(r, examined_, [&](const Entry& f) {
          if ((f.cy != e.cy || f.body > e.body) && !f.stretched) test(e, f);
        });
        continue;
      }
      const CellRange r{std::max(e.cx - 2, 0), std::max(e.cy - 2, 0), std::min(e.cx + 2, last_x),
                        std::min(e.cy + 2, last_y)};
      level.scan(r, examined_, [&](const Entry& f) {
        if (f.stretched ? (f.cy > e.cy || (f.cy == e.cy && f.body > e.body)) : f.body != e.body)
          test(e, f);
      });
    }
    // Against every coarser level, from whichever side has fewer bodies: a ground box scans the
    // boxes around it once rather than every box scanning for the ground.
    for (std::size_t m = l + 1; m < levels_.size(); ++m) {
      const Level& coarse = levels_[m];
      if (coarse.entries.size() < level.entries.size()) {
        for (const Entry& c : coarse.entries) {
          level.scan(level.cells_near(c.x, c.y, c.hx, c.hy, slack_), examined_,
                     [&](const Entry& f) { test(c, f); });
        }
      } else {
        for (const Entry& e : level.entries) {
          coarse.scan(coarse.cells_near(e.x, e.y, e.hx, e.hy, slack_), examined_,
                      [&](const Entry& f) { test(e, f); });
        }
      }
    }
  }
  // Each overlay body against the grid's bodies and the overlay bodies after it.
  for (const std::uint32_t i : members_) {
    const double x = bodies.x(i), y = bodies.y(i), hx = bodies.hx(i), hy = bodies.hy(i);
    const bool fixed = bodies.immovable(i);
    for (std::size_t l = 0; l < levels_.size(); ++l) {
      const Level& level = levels_[l];
      level.scan(level.cells_near(x, y, hx, hy, slack_), examined_, [&](const Entry& f) {
        if (!f.out && !(fixed && f.immovable) && within(x, y, hx, hy, f, gap)) {
          fn(std::min(i, f.body), std::max(i, f.body));
        }
      });
      const double rx = hx + level.small_half + slack_, ry = hy + level.small_half + slack_;
      scan_overlay(l, x, y, rx, ry, [&](std::uint32_t j) {
        if (j <= i || (fixed && bodies.immovable(j))) return;
        if ((hx + bodies.hx(j)) - std::abs(x - bodies.x(j)) > gap &&
            (hy + bodies.hy(j)) - std::abs(y - bodies.y(j)) > gap) {
          fn(i, j);
        }
      });
    }
  }
}

template <class Fn>
void Broadphase::for_each_overlap(const Bodies& bodies, std::uint32_t body, double tolerance,
                                  Fn&& fn) const {
  const double x = bodies.x(body), y = bodies.y(body), hx = bodies.hx(body), hy = bodies.hy(body);
  scan_all(x, y, hx, hy, margin_, [&](std::uint32_t j) {
    if (j != body && (hx + bodies.hx(j)) - std::abs(x - bodies.x(j)) > tolerance &&
        (hy + bodies.hy(j)) - std::abs(y - bodies.y(j)) > tolerance) {
      fn(j);
    }
  });
}

template <class Fn>
void Broadphase::for_each_stale_overlap(const Bodies& bodies, std::uint32_t body, double tolerance,
                                        Fn&& fn) const {
  const double x = bodies.x(body), y = bodies.y(body), hx = bodies.hx(body), hy = bodies.hy(body);
  if (!near_stale(body) || !stale_may_overlap(x, y, hx, hy, tolerance)) return;
  for (std::size_t l = 0; l < levels_.size(); ++l) {
    const Level& level = levels_[l];
    const double rx = hx + level.small_half + margin_, ry = hy + level.small_half + margin_;
    scan_overlay(l, x, y, rx, ry, [&](std::uint32_t j) {
      if (j != body && epoch_of_[j] > scan_ &&
          (hx + bodies.hx(j)) - std::abs(x - bodies.x(j)) > tolerance &&
          (hy + bodies.hy(j)) - std::abs(y - bodies.y(j)) > tolerance) {
        fn(j);
      }
    });
  }
}

template <class Fn>
void Broadphase::for_each_in_box(const Bodies& bodies, double x, double y, double hx, double hy,
                                 double slack, Fn&& fn) const {
  scan_all(x, y, hx, hy, margin_ + slack, [&](std::uint32_t j) {
    if ((hx + bodies.hx(j)) - std::abs(x - bodies.x(j)) >= -slack &&
        (hy + bodies.hy(j)) - std::abs(y - bodies.y(j)) >= -slack) {
      fn(j);
    }
  });
}

template <class Fn>
void Broadphase::for_each_stale_candidate(const Bodies& bodies, std::uint32_t body, Fn&& fn) const {
  const Entry& own = levels_[level_of_[body]].entries[entry_of_[body]];
  const double hx = bodies.hx(body), hy = bodies.hy(body);
  for (const Level& level : levels_) {
    level.scan(level.cells_near(own.x, own.y, hx, hy, 0.0), examined_,
               [&](const Entry& e) { fn(e.body); });
  }
}

}  // namespace chain::detail
