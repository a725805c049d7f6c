// SPDX-License-Identifier: MIT
#include "broadphase.h"

#include "buffer.h"

#include <bit>
#include <limits>
#include <utility>

namespace chain::detail {
namespace {

constexpr double kMinCell = 1.0e-6;
constexpr std::uint32_t kMaxCellsPerAxis = 1u << 30;
constexpr std::size_t kMaxLevels = 8;
// A level holds sizes up to this many times its median: cells stay within a few bodies.
constexpr double kLevelSpread = 2.0;

double largest_half(const Bodies& b, std::uint32_t i) {
  return std::max(b.hx(i), b.hy(i));
}

std::uint32_t cells_spanned(double lo, double hi, double inv_cell) {
  const double span = std::floor((hi - lo) * inv_cell);
  if (!(span < static_cast<double>(kMaxCellsPerAxis - 1))) return kMaxCellsPerAxis;
  return static_cast<std::uint32_t>(span) + 1;
}

}  // namespace

void Broadphase::configure(const Bodies& bodies) {
  ++generation_;
  const std::uint32_t n = bodies.size();
  level_of_.assign(n, 0);
  entry_of_.assign(n, 0);
  // Exact sizes: configure() runs when the body set changes, and costs O(n) then anyway.
  ref_.reserve(n);
  ref_.resize(n);
  stretch_.assign(n, Stretch{0.0f, 0.0f});
  stretched_ = false;
  in_overlay_.assign(n, 0);
  overlay_cx_.assign(n, 0);
  overlay_cy_.assign(n, 0);
  next_.assign(n, kNoSlot);
  prev_.assign(n, kNoSlot);
  epoch_of_.assign(n, 0);
  near_stale_.assign(n, 0);
  members_.clear();
  members_.reserve(n);
  unmarked_.clear();
  unmarked_.reserve(std::min<std::size_t>(n, 1024));
  stale_ = 0;
  levels_.clear();

  // By size, then slot: sorted as (size, slot) pairs, so that no comparison reads the bodies.
  std::vector<std::pair<double, std::uint32_t>> sized(n);
  for (std::uint32_t i = 0; i < n; ++i)
    sized[i] = {largest_half(bodies, i), i};
  std::sort(sized.begin(), sized.end());
  std::vector<std::uint32_t> by_size(n);
  for (std::uint32_t k = 0; k < n; ++k)
    by_size[k] = sized[k].second;
  std::vector<double> movable;
  std::size_t start = 0;
  while (start < n) {
    // The median size of the movable bodies left (of all left, if none moves) sets the level.
    movable.clear();
    for (std::size_t k = start; k < n; ++k) {
      if (!bodies.immovable(by_size[k])) movable.push_back(largest_half(bodies, by_size[k]));
    }
    const double median = movable.empty() ? largest_half(bodies, by_size[start + (n - start) / 2])
                                          : movable[movable.size() / 2];
    std::size_t end = start;
    while (end < n && largest_half(bodies, by_size[end]) <= kLevelSpread * median)
      ++end;
    if (levels_.size() + 1 == kMaxLevels) end = n;
    Level& level = levels_.emplace_back();
    level.bodies.assign(by_size.begin() + static_cast<std::ptrdiff_t>(start),
                        by_size.begin() + static_cast<std::ptrdiff_t>(end));
    std::sort(level.bodies.begin(), level.bodies.end());
    level.small_half = largest_half(bodies, by_size[end - 1]);
    for (const std::uint32_t i : level.bodies)
      level_of_[i] = static_cast<std::uint8_t>(levels_.size() - 1);
    start = end;
  }
  slack_ = levels_.empty() ? 0.0 : 0.25 * levels_.front().small_half;
  refile_ = 0.25 * slack_;
  for (Level& level : levels_) {
    level.cell = std::max(2.0 * level.small_half + slack_, kMinCell);
    level.inv_cell = 1.0 / level.cell;
    const std::uint32_t count = static_cast<std::uint32_t>(level.bodies.size());
    const std::uint32_t table = std::bit_ceil(std::max<std::uint32_t>(64u, 2u * count));
    level.mask = table - 1;
    level.cell_start.assign(table + 1, 0);
    level.cursor.assign(table, 0);
    level.keys.reserve(count), level.keys.resize(count);
    level.entries.reserve(count), level.entries.resize(count);
    level.overlay_head.assign(table, kNoSlot);
  }
}

void Broadphase::renumber(std::span<const std::uint32_t> order, Bodies::Spare& spare) {
  ++generation_;
  // Until the next build() only note_move() runs: it needs each body's filed place under its new
  // slot. The overlay is emptied; the next build() files everything anew.
  clear_overlay();
  spare.gather(ref_, order);
  spare.gather(stretch_, order);
  // Slot order within each level, as configure() leaves it; the lists keep their capacity.
  for (Level& level : levels_)
    level.bodies.clear();
  for (std::uint32_t slot = 0; slot < order.size(); ++slot)
    levels_[level_of_[order[slot]]].bodies.push_back(slot);
  for (std::size_t l = 0; l < levels_.size(); ++l) {
    for (const std::uint32_t slot : levels_[l].bodies)
      level_of_[slot] = static_cast<std::uint8_t>(l);
  }
}

void Broadphase::build(const Bodies& bodies, double dt, Vec2 gravity) {
  built_generation_ = generation_;
  margin_ = 0.0;
  clear_overlay();
  for (std::uint32_t i = 0; i < bodies.size(); ++i) {
    ref_[i] = {bodies.x(i), bodies.y(i)};
    stretch_[i] = {0.0f, 0.0f};
  }
  if (dt > 0.0) {
    // The way a body goes in kAheadSteps steps at its velocity before this step's gravity (a
    // body at rest on the ground has gravity's share of a step, which its support takes away).
    const double ahead = kAheadSteps * dt, least = 2.0 * refile_;
    for (std::uint32_t i = 0; i < bodies.movable_end; ++i) {
      const double g = i < bodies.dynamic_end ? bodies.gravity_scale[i] * dt : 0.0;
      const double way[2] = {(bodies.vx[i] - gravity.x * g) * ahead,
                             (bodies.vy[i] - gravity.y * g) * ahead};
      const double most = levels_[level_of_[i]].small_half;
      double* const centre = &ref_[i].x;
      float* const by = &stretch_[i].x;
      for (int axis = 0; axis < 2; ++axis) {
        if (!(std::abs(way[axis]) > least)) continue;  // NaN (an emptied slot) included
        // Rounded down to a float: the near-pair scan's two cells need the stretch no larger than
        // `most`, by less than the slack, which is as small as a quarter of the finest level's
        // largest half extent (a float of `most` rounded up could pass it by most * 2^-24).
        const double want = std::min(0.5 * std::abs(way[axis]), most);
        auto half = static_cast<float>(want);
        if (static_cast<double>(half) > want) half = std::nextafter(half, 0.0f);
        centre[axis] += way[axis] > 0.0 ? half : -half;
        by[axis] = half;
      }
    }
  }
  for (Level& level : levels_)
    level.build(bodies, ref_, stretch_, entry_of_);
  stretched_ = std::any_of(levels_.begin(), levels_.end(),
                           [](const Level& level) { return level.stretch > 0.0; });
}

void Broadphase::insert(const Bodies& bodies, std::uint32_t body) {
  const double half = std::max(bodies.hx(body), bodies.hy(body));
  std::uint8_t l = 0;
  while (levels_[l].small_half < half)
    ++l;
  if (const std::uint8_t old = level_of_[body]; old != l) {
    std::vector<std::uint32_t>& from = levels_[old].bodies;
    from.erase(std::lower_bound(from.begin(), from.end(), body));
    std::vector<std::uint32_t>& to = levels_[l].bodies;
    to.insert(std::upper_bound(to.begin(), to.end(), body), body);
    level_of_[body] = l;
  }
  refile(body, bodies.x(body), bodies.y(body));
}

void Broadphase::remove(std::uint32_t body) {
  Level& level = levels_[level_of_[body]];
  if (built() && entry_of_[body] != kNoSlot) level.entries[entry_of_[body]].out = 1;
  entry_of_[body] = kNoSlot;  // until build() files the slot again
  if (in_overlay_[body]) {
    unlink(body);
    in_overlay_[body] = 0;
    --level.overlay_members;
    members_.erase(std::find(members_.begin(), members_.end(), body));
    if (epoch_of_[body] > scan_) --stale_;
  }
  epoch_of_[body] = 0;
}

void Broadphase::clear_overlay() {
  for (const std::uint32_t i : members_) {
    if (!in_overlay_[i]) continue;
    Level& level = levels_[level_of_[i]];
    level.overlay_head[level.overlay_bucket(overlay_cx_[i], overlay_cy_[i])] = kNoSlot;
    in_overlay_[i] = 0;
  }
  for (Level& level : levels_)
    level.overlay_members = 0;
  members_.clear();
  stale_ = 0;
  next_mark_epoch();
  unmarked_.clear();
}

void Broadphase::mark_refiled() const {
  for (const Filed& f : unmarked_)
    mark_near(level_of_[f.body], f.x, f.y);
  unmarked_.clear();
}

void Broadphase::mark_near(std::size_t l, double x, double y) const {
  // A grid body k (filed at entry e, now at most margin_ <= refile_ from it) and the body filed at
  // (x, y) (half extents at most its level's largest, and moving at most refile_ before it is filed
  // again) can overlap only if their filed places are closer than both half extents and both
  // refile distances: the test below with a gap of -2 refile_.
  const double h = levels_[l].small_half, reach = 2.0 * refile_;
  for (const Level& level : levels_) {
    level.scan(level.cells_near(x, y, h, h, reach), examined_, [&](const Entry& e) {
      if (!e.out && within(x, y, h, h, e, -reach)) near_stale_[e.body] = mark_epoch_;
    });
  }
}

void Broadphase::unlink(std::uint32_t body) {
  Level& level = levels_[level_of_[body]];
  const std::uint32_t p = prev_[body], n = next_[body];
  if (p != kNoSlot) {
    next_[p] = n;
  } else {
    level.overlay_head[level.overlay_bucket(overlay_cx_[body], overlay_cy_[body])] = n;
  }
  if (n != kNoSlot) prev_[n] = p;
}

void Broadphase::refile(std::uint32_t body, double x, double y) {
  Level& level = levels_[level_of_[body]];
  if (in_overlay_[body]) {
    unlink(body);
  } else {
    in_overlay_[body] = 1;
    ++level.overlay_members;
    members_.push_back(body);
    // Until build() runs after a configure() or renumber(), entry_of_ names the entries of the old
    // slots (of another level, maybe): nothing reads them before build() files every body anew.
    // A slot remove() emptied has no entry until then.
    if (built() && entry_of_[body] != kNoSlot) level.entries[entry_of_[body]].out = 1;
  }
  if (epoch_of_[body] <= scan_) {
    if (stale_++ == 0) {
      stale_lo_ = {std::numeric_limits<double>::infinity(),
                   std::numeric_limits<double>::infinity()};
      stale_hi_ = {-stale_lo_.x, -stale_lo_.y};
    }
  }
  epoch_of_[body] = scan_ + 1;
  // Its level's largest half extent stands for its own: no per-body sizes to keep in slot order.
  const double h = level.small_half;
  stale_lo_ = {std::min(stale_lo_.x, x - h), std::min(stale_lo_.y, y - h)};
  stale_hi_ = {std::max(stale_hi_.x, x + h), std::max(stale_hi_.y, y + h)};
  const std::int32_t cx = level.overlay_x(x), cy = level.overlay_y(y);
  overlay_cx_[body] = cx;
  overlay_cy_[body] = cy;
  std::uint32_t& head = level.overlay_head[level.overlay_bucket(cx, cy)];
  prev_[body] = kNoSlot;
  next_[body] = head;
  if (head != kNoSlot) prev_[head] = body;
  head = body;
  ref_[body] = {x, y};
  stretch_[body] = {0.0f, 0.0f};
  if (built()) unmarked_.push_back({body, x, y});
}

void Broadphase::Level::build(const Bodies& b, std::span<const Point> at,
                              std::span<const Stretch> by, std::vector<std::uint32_t>& entry_of) {
  double min_x = std::numeric_limits<double>::max(), min_y = min_x;
  double max_x = std::numeric_limits<double>::lowest(), max_y = max_x;
  stretch = 0.0;
  for (const std::uint32_t i : bodies) {
    min_x = std::min(min_x, at[i].x);
    max_x = std::max(max_x, at[i].x);
    min_y = std::min(min_y, at[i].y);
    max_y = std::max(max_y, at[i].y);
    stretch = std::max(stretch, static_cast<double>(std::max(by[i].x, by[i].y)));
  }
  // A level every body of which has left (emptied slots, NaN centres, skip the min/max; bodies
  // refiled to other levels) has no bounds: one cell at the origin, as a level's grid needs one.
  if (!(min_x <= max_x)) min_x = max_x = min_y = max_y = 0.0;
  // Half a cell below the lowest centre: scenes built on a lattice (stacks, rows) then have
  // their centres mid-cell, and a query around a box spans 3 cells a side, not 4.
  origin_x = min_x - 0.5 * cell;
  origin_y = min_y - 0.5 * cell;
  width = cells_spanned(origin_x, max_x, inv_cell);
  height = cells_spanned(origin_y, max_y, inv_cell);
  dense = static_cast<std::uint64_t>(width) * height <= static_cast<std::uint64_t>(mask) + 1;

  // Counting sort by bucket; stable, so solve order holds within a bucket. The level may have
  // gained or lost slots since configure() (Broadphase::insert).
  resize_buffer(keys, bodies.size());
  resize_buffer(entries, bodies.size());
  std::fill(cell_start.begin(), cell_start.end(), 0u);
  for (std::size_t k = 0; k < bodies.size(); ++k) {
    const std::uint32_t i = bodies[k];
    keys[k] = bucket(cell_x(at[i].x), cell_y(at[i].y));
    ++cell_start[keys[k] + 1];
  }
  for (std::size_t k = 1; k < cell_start.size(); ++k)
    cell_start[k] += cell_start[k - 1];
  std::copy(cell_start.begin(), cell_start.end() - 1, cursor.begin());
  for (std::size_t k = 0; k < bodies.size(); ++k) {
    // The cells again (a few operations) rather than kept from the pass above: 8 bytes a body.
    const std::uint32_t i = bodies[k];
    entry_of[i] = cursor[keys[k]]++;
    const std::uint8_t immovable = b.immovable(i) ? 1 : 0;
    const std::uint8_t stretched = by[i].x != 0.0f || by[i].y != 0.0f ? 1 : 0;
    entries[entry_of[i]] =
        Entry{i,         cell_x(at[i].x), cell_y(at[i].y), immovable,         0,
              stretched, at[i].x,         at[i].y,         b.hx(i) + by[i].x, b.hy(i) + by[i].y};
  }
}

}  // namespace chain::detail
