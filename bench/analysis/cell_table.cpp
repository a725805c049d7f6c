#include "cell_table.h"

#include <bit>

namespace chainbench {

void CellTable::sort() {
  // Counting sort by bucket; stable, so boxes keep their order of addition within a bucket (the
  // order pairs are reported in). Twice as many buckets as entries: most lookups of a box at rest
  // meet an empty one, and the table stays small enough for the cache.
  const std::uint64_t table = std::bit_ceil(std::max<std::uint64_t>(64, 2 * entries_.size()));
  mask_ = table - 1;
  start_.assign(table + 1, 0);
  for (const Entry& e : entries_)
    ++start_[bucket(e.cx, e.cy) + 1];
  for (std::size_t b = 1; b < start_.size(); ++b)
    start_[b] += start_[b - 1];
  sorted_.resize(entries_.size());
  // start_[b] serves as the fill cursor of bucket b, with no buffer of cursors to allocate ...
  for (const Entry& e : entries_)
    sorted_[start_[bucket(e.cx, e.cy)]++] = e;
  for (std::size_t b = start_.size() - 1; b > 0; --b)  // ... and is shifted back afterwards
    start_[b] = start_[b - 1];
  start_[0] = 0;
}

}  // namespace chainbench
