// SPDX-License-Identifier: MIT
// The overlap test of the near-list walks.
//
// A step tests every near pair at least twice (the contacts, then the walls' walk), and most
// tests fail. With SSE2 (every x86-64), x and y go through the same operations as the two lanes
// of one register: no branch between the axes and about two thirds of the scalar instructions.
// Every lane rounds exactly as the scalar expression
//   (hx + hx_j) - |x - x_j| > tol && (hy + hy_j) - |y - y_j| > tol
// does (the same IEEE operations on the same operands in the same order; |d| clears the sign
// bit, as std::abs does), so both forms give the same answer for every pair, bit for bit.
// The boxes are read through one pointer: Bodies::box is a vector the callers also write through
// (placements, the output list), and a walk through the vector reloads its data pointer for
// every entry.
#pragma once

#include "bodies.h"

#include <cmath>
#include <cstdint>
#include <span>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace chain::detail {

// The test's constants, made once where a walk over many lists begins.
struct OverlapTest {
  explicit OverlapTest(double tol)
#if defined(__SSE2__)
      : minus_tolerance(_mm_set1_pd(-tol)),
        magnitude(_mm_castsi128_pd(_mm_set1_epi64x(0x7fffffffffffffff)))
#else
      : tolerance(tol)
#endif
  {
  }
#if defined(__SSE2__)
  __m128d minus_tolerance, magnitude;
#else
  double tolerance;
#endif
};

// Lists of bodies to test are kept as slot * kEntryScale: the offset of the body's Box in
// doubles. The walk then finds a box at base + 8 * entry, one lea, where a slot needs a shift
// and an add (a Box is 32 bytes, past the largest scale an x86 address takes): one of the
// seventeen instructions every entry of every walk costs.
inline constexpr std::uint32_t kEntryScale = 4;
static_assert(sizeof(Bodies::Box) == kEntryScale * sizeof(double));
// Slots up to this many fit an entry.
inline constexpr std::uint32_t kMaxEntrySlots = 0xffffffffu / kEntryScale;

// fn(j), in list order, for every body j of `list` (entries: slot * kEntryScale) that overlaps
// body i by more than the tolerance on both axes: the test of overlapping() in step_context.h,
// operand for operand.
template <class Fn>
inline void for_each_hit(const Bodies::Box* box, std::uint32_t i,
                         std::span<const std::uint32_t> list, const OverlapTest& test, Fn&& fn) {
#if defined(__SSE2__)
  // Written so that every destructive SSE2 operation lands on a value loaded for this entry, and
  // no loop-invariant register needs a copy: |x_j - x| is |x - x_j| (a - b is -(b - a) exactly),
  // hx_j + hx is hx + hx_j, and with depth = (hx + hx_j) - |x - x_j|, the lane computes -depth
  // exactly and tests -depth < -tol, which holds exactly when depth > tol.
  const __m128d centre = _mm_loadu_pd(box[i].center), half = _mm_loadu_pd(box[i].half);
  const __m128d minus_tolerance = test.minus_tolerance, magnitude = test.magnitude;
  // The boxes as bytes: an entry times 8 is the offset of its box's centre, and 16 more its half
  // extents (Box::center, Box::half).
  const char* const bytes = reinterpret_cast<const char*>(box);
  for (const std::uint32_t e : list) {
    const char* const b = bytes + std::size_t{e} * sizeof(double);
    const __m128d b_centre = _mm_loadu_pd(reinterpret_cast<const double*>(b));
    const __m128d b_half = _mm_loadu_pd(reinterpret_cast<const double*>(b + 2 * sizeof(double)));
    const __m128d distance = _mm_and_pd(_mm_sub_pd(b_centre, centre), magnitude);
    const __m128d minus_depth = _mm_sub_pd(distance, _mm_add_pd(b_half, half));
    if (_mm_movemask_pd(_mm_cmplt_pd(minus_depth, minus_tolerance)) == 3) fn(e / kEntryScale);
  }
#else
  const double tol = test.tolerance;
  const double x = box[i].center[0], y = box[i].center[1];
  const double hx = box[i].half[0], hy = box[i].half[1];
  for (const std::uint32_t e : list) {
    const std::uint32_t j = e / kEntryScale;
    const Bodies::Box& b = box[j];
    if ((hx + b.half[0]) - std::abs(x - b.center[0]) > tol &&
        (hy + b.half[1]) - std::abs(y - b.center[1]) > tol) {
      fn(j);
    }
  }
#endif
}

}  // namespace chain::detail
