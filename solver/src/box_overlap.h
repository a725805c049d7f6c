// The overlap test of the near-list walks, with the list's boxes read through one pointer.
//
// Bodies::box is a vector the walks' callers also write through (placements, pushes onto the
// output), so a walk written against the vector reloads its data pointer for every entry; here it
// is read once per list.
#pragma once

#include "bodies.h"

#include <cmath>
#include <cstdint>
#include <span>

namespace chain::detail {

// fn(j), in list order, for every body j of `list` that overlaps body i by more than `tol` on
// both axes; the same test as overlapping() in step_context.h, operand for operand.
template <class Fn>
inline void for_each_hit(const Bodies::Box* box, std::uint32_t i,
                         std::span<const std::uint32_t> list, double tol, Fn&& fn) {
  const double x = box[i].center[0], y = box[i].center[1];
  const double hx = box[i].half[0], hy = box[i].half[1];
  for (const std::uint32_t j : list) {
    const Bodies::Box& b = box[j];
    if ((hx + b.half[0]) - std::abs(x - b.center[0]) > tol &&
        (hy + b.half[1]) - std::abs(y - b.center[1]) > tol) {
      fn(j);
    }
  }
}

}  // namespace chain::detail
