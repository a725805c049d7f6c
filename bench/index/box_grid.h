// SPDX-License-Identifier: MIT
// A uniform grid over a fixed set of axis-aligned boxes, for finding every box that touches a
// query box in time proportional to the cells the query covers and the boxes in them, instead of
// to all the boxes: what keeps a query per cluster, body or pair linear in the scene.
//
// Each box is held in every cell it covers, in a CellTable (which reports a box touching the query
// in several cells once). A box covering more than CellTable::kMaxCells cells is tested against
// every query instead, and a query covering more cells than there are boxes tests every box.
#pragma once

#include "index/cell_table.h"

#include <cstdint>
#include <span>
#include <vector>

namespace chainbench {

class BoxGrid {
 public:
  using Box = CellTable::Box;
  // `boxes` must be finite; `cell` is the cells' side (about the size of most boxes).
  BoxGrid(std::span<const Box> boxes, double cell);

  // fn(k) once for every box k (its index in `boxes`) that overlaps or touches `q`.
  template <class Fn>
  void for_each_touching(const Box& q, Fn&& fn) const;

 private:
  std::vector<Box> boxes_;
  CellTable table_;
  std::vector<std::uint32_t> giants_;
};

template <class Fn>
void BoxGrid::for_each_touching(const Box& q, Fn&& fn) const {
  const CellTable::Cells c = table_.cover(q);
  if (c.count() > static_cast<double>(boxes_.size())) {  // walking every box is cheaper
    for (std::uint32_t k = 0; k < boxes_.size(); ++k) {
      if (CellTable::touch(q, boxes_[k])) fn(static_cast<std::size_t>(k));
    }
    return;
  }
  table_.for_each_in_cells(q, c, [&](std::uint32_t k) { fn(static_cast<std::size_t>(k)); });
  for (const std::uint32_t g : giants_) {
    if (CellTable::touch(q, boxes_[g])) fn(static_cast<std::size_t>(g));
  }
}

}  // namespace chainbench
