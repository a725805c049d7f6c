#include "box_grid.h"

#include <bit>

namespace chainbench {

BoxGrid::BoxGrid(std::span<const Box> boxes, double cell_size)
    : boxes_(boxes.begin(), boxes.end()), inv_cell_(1.0 / std::max(cell_size, 1e-9)) {
  std::vector<Entry> entries;
  for (std::size_t k = 0; k < boxes_.size(); ++k) {
    const Box& b = boxes_[k];
    const std::int64_t cx0 = cell(b.x0), cx1 = cell(b.x1), cy0 = cell(b.y0), cy1 = cell(b.y1);
    // Compared in double: a box of a huge world can span more cells than an int64 holds.
    const double cells = (static_cast<double>(cx1) - static_cast<double>(cx0) + 1.0) *
                         (static_cast<double>(cy1) - static_cast<double>(cy0) + 1.0);
    if (cells > static_cast<double>(kMaxCells)) {
      giants_.push_back(static_cast<std::uint32_t>(k));
      continue;
    }
    for (std::int64_t cy = cy0; cy <= cy1; ++cy) {
      for (std::int64_t cx = cx0; cx <= cx1; ++cx)
        entries.push_back({static_cast<std::uint32_t>(k), cx, cy});
    }
  }
  // Counting sort by bucket.
  const std::uint64_t table = std::bit_ceil(std::max<std::uint64_t>(64, 2 * entries.size()));
  mask_ = table - 1;
  start_.assign(table + 1, 0);
  for (const Entry& e : entries)
    ++start_[bucket(e.cx, e.cy) + 1];
  for (std::size_t b = 1; b < start_.size(); ++b)
    start_[b] += start_[b - 1];
  sorted_.resize(entries.size());
  std::vector<std::uint32_t> cursor(start_.begin(), start_.end() - 1);
  for (const Entry& e : entries)
    sorted_[cursor[bucket(e.cx, e.cy)]++] = e;
}

}  // namespace chainbench
