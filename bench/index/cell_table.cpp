// SPDX-License-Identifier: MIT
#include "index/cell_table.h"

#include <bit>

namespace chainbench {

void CellTable::sort(std::span<const Box> boxes) {
  // Dense when the occupied range has at most 4 cells per entry: its table of buckets is then no
  // bigger than a hashed one of a few buckets per entry, and keeps space order.
  dense_ = false;
  if (!entries_.empty()) {
    range_ = {entries_[0].cx, entries_[0].cy, entries_[0].cx, entries_[0].cy};
    for (const Entry& e : entries_) {
      range_ = {std::min(range_.x0, e.cx), std::min(range_.y0, e.cy), std::max(range_.x1, e.cx),
                std::max(range_.y1, e.cy)};
    }
    dense_ = range_.count() <= 4.0 * static_cast<double>(entries_.size());
    width_ = range_.x1 - range_.x0 + 1;
  }
  // Hashed: twice as many buckets as entries, so that most lookups of a box at rest meet an
  // empty one, and the table stays small enough for the cache.
  const std::uint64_t table = dense_
                                  ? static_cast<std::uint64_t>(range_.count())
                                  : std::bit_ceil(std::max<std::uint64_t>(64, 2 * entries_.size()));
  mask_ = table - 1;
  // Counting sort by bucket; stable, so boxes keep their order of addition within a bucket (the
  // order pairs are reported in).
  start_.assign(table + 1, 0);
  for (const Entry& e : entries_)
    ++start_[bucket(e.cx, e.cy) + 1];
  for (std::size_t b = 1; b < start_.size(); ++b)
    start_[b] += start_[b - 1];
  sorted_.resize(entries_.size());
  sorted_box_.resize(entries_.size());
  // start_[b] serves as the fill cursor of bucket b, with no buffer of cursors to allocate ...
  for (const Entry& e : entries_) {
    const std::uint32_t at = start_[bucket(e.cx, e.cy)]++;
    sorted_[at] = e;
    sorted_box_[at] = boxes[e.index];
  }
  for (std::size_t b = start_.size() - 1; b > 0; --b)  // ... and is shifted back afterwards
    start_[b] = start_[b - 1];
  start_[0] = 0;
}

}  // namespace chainbench
