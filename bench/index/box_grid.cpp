// SPDX-License-Identifier: MIT
#include "index/box_grid.h"

namespace chainbench {

BoxGrid::BoxGrid(std::span<const Box> boxes, double cell_size)
    : boxes_(boxes.begin(), boxes.end()), table_(cell_size) {
  for (std::size_t k = 0; k < boxes_.size(); ++k) {
    const CellTable::Cells c = table_.cover(boxes_[k]);
    if (c.count() > CellTable::kMaxCells) {
      giants_.push_back(static_cast<std::uint32_t>(k));
      continue;
    }
    table_.add(static_cast<std::uint32_t>(k), c);
  }
  table_.sort(boxes_);
}

}  // namespace chainbench
