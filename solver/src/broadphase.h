// SPDX-License-Identifier: MIT
// Broadphase: uniform grids over body centres, one per size class, rebuilt by a counting sort at
// every pass.
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
// A body moved after build() stays in the entry it was built into while it is within
// refile_distance() (a quarter of the slack) of where it was filed; queries widen by the largest
// such displacement, and test current positions from the bodies. A body that moves further (a
// far push, a fast body) is filed again at its new place in the overlay: a hashed grid of the same
// cells over unbounded cell coordinates, one linked list per bucket, which queries scan as well.
// So no query ever widens by more than refile_distance(), however far any body went: one far push
// no longer makes every later query scan a region as wide as that push (work per query stays
// bounded by the bodies around the query, not by the largest move of the step). Integration
// notes its moves too, so telling whether the near pairs still hold needs no pass over the bodies.
//
// A body moving steadily (a pushed row, a train, a blade, a falling box) would be filed again
// every step or two, and once an eighth of the bodies were, every near pair was scanned again. So
// build() files a body that moves at its box stretched along the way its velocity takes it over
// the next kAheadSteps steps (Box2D's fat boxes, enlarged by the predicted displacement, play that
// part): the body stays where it is filed while its box is within that stretched box grown by
// refile_distance(), and the near pairs are those of the stretched boxes. A body at rest, or
// slower than takes it 2 refile distances in that time, is filed at its box, as before.
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
  // The slots were renumbered (slot i was order[i]): files each body under its new slot, through
  // `spare` (the buffer Bodies::permute used). Like configure(), it changes generation(), and the
  // next query needs build().
  void renumber(std::span<const std::uint32_t> order, Bodies::Spare& spare);
  // Buckets every body at its current position. With dt > 0 (s), a movable body whose velocity at
  // the step's start (its velocity less this step's gravity) takes it more than 2
  // refile_distance() along an axis in kAheadSteps steps of dt is filed at its box stretched
  // over that way, by at most its level's largest half extent.
  void build(const Bodies& bodies, double dt = 0.0, Vec2 gravity = {0.0, 0.0});
  static constexpr double kAheadSteps = 8.0;
  // Whether a body of this largest half extent fits a level (no larger than the largest body of
  // some level), so that insert() can take it without configure().
  bool fits(double largest_half) const {
    return !levels_.empty() && largest_half <= levels_.back().small_half;
  }
  // Slot `body` of a dead body (remove()) now holds a new one, which fits(): files it in the
  // finest level that holds its size, in the overlay where it is (filed again, as a far push is),
  // so that the near pairs serve on and generation() does not change.
  void insert(const Bodies& bodies, std::uint32_t body);
  // The body of slot `body` is gone (Bodies::kill): it leaves the grid and the overlay, and the
  // slot keeps its level until insert() fills it.
  void remove(std::uint32_t body);
  // Changes whenever the body set changes (configure()) or the slots are renumbered.
  std::uint64_t generation() const { return generation_; }
  // build() ran since the last configure() or renumber(): queries may be made (every move since
  // having been noted).
  bool built() const { return built_generation_ == generation_; }
  // How many bodies were filed again since the near pairs were last scanned.
  std::uint32_t stale_count() const { return stale_; }
  // Every move of a body after build() must be noted, integration included. A body further than
  // refile_distance() from where it was last filed is filed again where it is now.
  void note_move(std::uint32_t body, double x, double y) {
    const double d = distance(body, x, y);
    margin_ = std::max(margin_, std::min(d, refile_));
    if (d > refile_) [[unlikely]]
      refile(body, x, y);
  }
  // note_move() for bodies moved at once in blocks: distance() reads, and once the blocks are
  // done, note_moves() takes the largest distance of them all and the bodies further than
  // refile_distance(), in slot order. The same as note_move() for each body in slot order.
  // How far the body's box at (x, y) reaches out of the box it is filed at, on either axis.
  double distance(std::uint32_t body, double x, double y) const {
    const Point& r = ref_[body];
    // A world filed with no stretch (at rest) skips their loads: the walls' loop notes every
    // placement, and they cost a resting pyramid 2% of its step.
    if (!stretched_) return std::max(std::abs(x - r.x), std::abs(y - r.y));
    const Stretch& e = stretch_[body];
    return std::max(std::abs(x - r.x) - e.x, std::abs(y - r.y) - e.y);
  }
  // Where each body was last filed (the centre of its filed box) and by how much that box is
  // larger than the body's on each axis, for loops that compute distance() themselves (as the
  // same operations on both axes at once).
  const Point* filed_at() const { return ref_.data(); }
  struct Stretch {  // in floats: 8 bytes a body, and the filed box is made with the same values
    float x, y;
  };
  const Stretch* stretched_by() const { return stretch_.data(); }
  void note_moves(const Bodies& bodies, double largest, std::span<const std::uint32_t> far) {
    margin_ = std::max(margin_, std::min(largest, refile_));
    for (const std::uint32_t i : far)
      refile(i, bodies.x(i), bodies.y(i));
  }
  // True while no body was filed again since the near pairs were last scanned: every pair that
  // can overlap now is a near pair of that scan (each body has moved at most refile_distance(),
  // a quarter of the slack, from where the scan saw it).
  bool near_pairs_hold() const { return stale_ == 0; }
  // Body was filed again since the near pairs were last scanned: its near pairs are out of date,
  // and the other bodies' near pairs may miss it.
  bool stale(std::uint32_t body) const { return in_overlay_[body] && epoch_of_[body] > scan_; }
  // fn(body) for every stale body, in the order they were filed again (callers keep only an
  // order-free answer).
  template <class Fn>
  void for_each_stale(Fn&& fn) const {
    if (stale_ == 0) return;
    for (const std::uint32_t i : members_) {
      if (stale(i)) fn(i);
    }
  }
  // False when no body filed again since the near pairs were last scanned can now overlap the
  // box (x +- hx, y +- hy) by more than `tolerance`: the box's overlaps are all among its near
  // pairs. The test is against a box around every place such a body was filed, grown by the
  // largest half extent of its level and the refile distance (it moved at most that far since),
  // so it takes four comparisons however many bodies are stale.
  // False when no body filed again since the near pairs were last scanned was filed close
  // enough to `body` (a body not filed again since) to overlap it before being filed again:
  // refile() marks every grid body around the new place. Always true for a body in the overlay
  // (filed there before the last scan): marking those too cost more than their probes.
  bool near_stale(std::uint32_t body) const {
    if (!unmarked_.empty()) [[unlikely]]
      mark_refiled();
    return near_stale_[body] == mark_epoch_ || in_overlay_[body];
  }
  bool stale_may_overlap(double x, double y, double hx, double hy, double tolerance) const {
    const double g = refile_ - tolerance;
    return stale_ != 0 && x + hx + g > stale_lo_.x && x - hx - g < stale_hi_.x &&
           y + hy + g > stale_lo_.y && y - hy - g < stale_hi_.y;
  }
  // Pairs closer than this are near pairs.
  double slack() const { return slack_; }
  // How far a body may move from where it was filed before it is filed again: a quarter of the
  // slack, so that two bodies that both stayed within it closed by less than the slack.
  double refile_distance() const { return refile_; }
  // Candidate bodies examined by queries and pair scans since configure(): the broadphase's work.
  std::uint64_t examined() const { return examined_; }

  // fn(i, j) with i < j, once for every pair whose boxes are less than slack() apart on both
  // axes where the grid and the overlay have them filed, except pairs of two immovable bodies.
  // Call right after build(), or later: bodies in the overlay are filed again where they are now,
  // first. Afterwards no body is stale.
  template <class Fn>
  void for_each_near_pair(const Bodies& bodies, Fn&& fn);

  // fn(j) once for every body j != body whose box now overlaps body's box by more than
  // `tolerance` on both axes, in an order that depends on where the bodies were filed (the last
  // build() and the overlay): callers that need an order sort what they find.
  template <class Fn>
  void for_each_overlap(const Bodies& bodies, std::uint32_t body, double tolerance, Fn&& fn) const;

  // fn(j) once for every body whose box now comes within `slack` of the box (x +- hx, y +- hy)
  // on both axes (slack 0: touching counts), in an order that depends on where the bodies were
  // filed: callers that need an order sort what they find, or keep only an order-free answer.
  template <class Fn>
  void for_each_in_box(const Bodies& bodies, double x, double y, double hx, double hy, double slack,
                       Fn&& fn) const;

  // fn(j) once for every stale body j != body whose box now overlaps body's box by more than
  // `tolerance` on both axes: with body's near pairs, every body it overlaps.
  template <class Fn>
  void for_each_stale_overlap(const Bodies& bodies, std::uint32_t body, double tolerance,
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
    std::uint8_t immovable;
    std::uint8_t out;        // the body is filed in the overlay now: this entry no longer counts
    std::uint8_t stretched;  // its box is stretched along its way (hx, hy include the stretch)
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
    double stretch = 0.0;     // largest stretch_ of its bodies at build(): 0 or at most small_half
    double origin_x = 0.0, origin_y = 0.0;
    std::uint32_t width = 1, height = 1, mask = 63;
    bool dense = true;                  // every cell has a bucket of its own
    std::vector<std::uint32_t> bodies;  // slots, in solve order
    std::vector<std::uint32_t> cell_start, cursor, keys;
    std::vector<Entry> entries;               // grouped by bucket, solve order within a bucket
    std::vector<std::uint32_t> overlay_head;  // per bucket: first overlay body, or kNoSlot
    std::uint32_t overlay_members = 0;        // bodies of this level in the overlay: 0, no probe

    // Overlay cells: the same cells, unbounded (a far push may leave the built bounding box).
    static std::int32_t unbounded(double c) {
      constexpr double kLimit = 1 << 30;
      if (!(c > -kLimit)) return -(1 << 30);
      if (c >= kLimit) return 1 << 30;
      return static_cast<std::int32_t>(std::floor(c));
    }
    std::int32_t overlay_x(double x) const { return unbounded((x - origin_x) * inv_cell); }
    std::int32_t overlay_y(double y) const { return unbounded((y - origin_y) * inv_cell); }
    std::uint32_t overlay_bucket(std::int32_t cx, std::int32_t cy) const {
      return (static_cast<std::uint32_t>(cx) * 0x9e3779b1u ^
              static_cast<std::uint32_t>(cy) * 0x85ebca77u) &
             mask;
    }

    std::int32_t cell_x(double x) const { return clamp_cell((x - origin_x) * inv_cell, width); }
    std::int32_t cell_y(double y) const { return clamp_cell((y - origin_y) * inv_cell, height); }
    std::uint32_t bucket(std::int32_t cx, std::int32_t cy) const {
      return (static_cast<std::uint32_t>(cy) * width + static_cast<std::uint32_t>(cx)) & mask;
    }
    // The cells whose bodies' filed boxes may reach the box (x +- hx, y +- hy) grown by pad.
    CellRange cells_near(double x, double y, double hx, double hy, double pad) const {
      const double rx = hx + small_half + stretch + pad, ry = hy + small_half + stretch + pad;
      return {cell_x(x - rx), cell_y(y - ry), cell_x(x + rx), cell_y(y + ry)};
    }
    // Entries for the filed boxes: centres `at`, half extents the bodies' grown by `by`.
    void build(const Bodies& bodies, std::span<const Point> at, std::span<const Stretch> by,
               std::vector<std::uint32_t>& entry_of);
    template <class Fn>
    void scan(CellRange r, std::uint64_t& examined, Fn&& fn) const;
  };

  static std::int32_t clamp_cell(double c, std::uint32_t count) {
    if (!(c >= 0.0)) return 0;
    if (c >= static_cast<double>(count - 1)) return static_cast<std::int32_t>(count - 1);
    return static_cast<std::int32_t>(c);
  }
  static bool within(double x, double y, double hx, double hy, const Entry& e, double gap) {
    return (hx + e.hx) - std::abs(x - e.x) > gap && (hy + e.hy) - std::abs(y - e.y) > gap;
  }

  // Files body in the overlay at (x, y) (moving it there if it is in already).
  void refile(std::uint32_t body, double x, double y);
  // Marks near_stale() every grid body that a body of level l filed at (x, y) may overlap before
  // it is filed again.
  void mark_near(std::size_t l, double x, double y) const;
  // mark_near() for every place a body was filed at since the marks were last made: when first
  // asked, so that a step whose refiled bodies send it to a new scan makes none.
  void mark_refiled() const;
  void clear_overlay();
  void unlink(std::uint32_t body);
  // The counters above are 32 bits (4 bytes a body each, not 8): before one would wrap, every
  // body's copy is reset, so that no old value matches or exceeds a new one.
  void next_scan() {
    if (scan_ < 0xfffffff0u) [[likely]]
      return;
    std::fill(epoch_of_.begin(), epoch_of_.end(), 0u);
    scan_ = 0;
  }
  void next_mark_epoch() {
    if (++mark_epoch_ != 0) [[likely]]
      return;
    std::fill(near_stale_.begin(), near_stale_.end(), 0u);
    mark_epoch_ = 1;
  }
  // fn(j) for every overlay body of level l filed in a cell the box (x +- rx, y +- ry) reaches.
  template <class Fn>
  void scan_overlay(std::size_t l, double x, double y, double rx, double ry, Fn&& fn) const;
  // Both the grid and the overlay: fn(j) for every body that may come within `pad` of the box.
  template <class Fn>
  void scan_all(double x, double y, double hx, double hy, double pad, Fn&& fn) const;

  std::vector<Level> levels_;
  std::vector<std::uint8_t> level_of_;   // per slot
  std::vector<std::uint32_t> entry_of_;  // per slot: index in its level's entries
  // Per slot, where the body was last filed (by build() or in the overlay): x and y together, as
  // every note_move() reads both; the centre of its filed box, stretched along its way by
  // stretch_ a side on each axis (0 in the overlay and for a body filed at its box).
  std::vector<Point> ref_;
  std::vector<Stretch> stretch_;
  bool stretched_ = false;  // some stretch_ is not 0
  // The overlay, per slot: in it or not, its cell there, its bucket list's links, and the scan
  // after which it was last filed (stale when later than scan_).
  std::vector<std::uint8_t> in_overlay_;
  std::vector<std::int32_t> overlay_cx_, overlay_cy_;
  std::vector<std::uint32_t> next_, prev_;
  std::vector<std::uint32_t> epoch_of_;
  // Per slot: mark_epoch_ when some body filed again since the last scan or clear_overlay() was
  // filed near it (near_stale()).
  mutable std::vector<std::uint32_t> near_stale_;
  std::uint32_t mark_epoch_ = 1;
  struct Filed {
    std::uint32_t body;
    double x, y;
  };
  mutable std::vector<Filed> unmarked_;  // places filed at since the marks were made
  std::vector<std::uint32_t> members_;   // overlay bodies, in the order they entered it
  std::uint32_t scan_ = 0;               // near-pair scans so far, modulo next_scan()
  std::uint32_t stale_ = 0;              // bodies filed again since the last scan
  Point stale_lo_{}, stale_hi_{};        // around their boxes where they were filed since
  double margin_ = 0.0;                  // largest distance() of a body not filed again
  double slack_ = 0.0;
  double refile_ = 0.0;
  std::uint64_t generation_ = 0;
  std::uint64_t built_generation_ = ~std::uint64_t{0};
  mutable std::uint64_t examined_ = 0;
};

}  // namespace chain::detail

// The templates above: the grid's and the overlay's scans, the near-pair scan and the queries.
#include "broadphase_scans.h"
