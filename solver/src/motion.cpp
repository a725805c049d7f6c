// SPDX-License-Identifier: MIT
#include "motion.h"

#include "buffer.h"

#include <algorithm>
#include <cmath>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace chain::detail {

// The one loop every step runs over every body. Array pointers are held in locals and every value
// is read once and written once: the arrays are separate vectors, which the compiler must assume
// may alias each other and the vectors' own bookkeeping, so anything else reloads them all on
// every body.
template <bool kDynamic, bool kFindFast, bool kKeepVelocities>
void Motion::integrate_range(Bodies& b, Broadphase& broadphase, Vec2 gravity, double dt,
                             std::uint32_t begin, std::uint32_t end, std::uint32_t out,
                             Notes& notes) {
  constexpr double share = kDynamic ? kFastDynamicShare : kFastKinematicShare;
  double* const vel_x = b.vx.data();
  double* const vel_y = b.vy.data();
  const double* const drive_x = b.drive_x.data();
  const double* const drive_y = b.drive_y.data();
  const std::uint8_t* const driven = b.driven.data();
  const double* const gravity_scale = b.gravity_scale.data();
  Bodies::Box* const boxes = b.box.data();
  Point* const start = b.start.data();
  Point* const pre = pre_velocity.data();
  std::uint32_t* const fast_out = fast_.data() + out;
  std::uint32_t* const far_out = far_.data() + out;
  std::uint32_t count = notes.fast, far = notes.far;
  double largest = notes.largest;
  const double refile = broadphase.refile_distance();
#if defined(__SSE2__)
  const __m128d step = _mm_set1_pd(dt);
  const __m128d magnitude = _mm_castsi128_pd(_mm_set1_epi64x(0x7fffffffffffffff));
  const Point* const filed_at = broadphase.filed_at();
  const Broadphase::Stretch* const stretched_by = broadphase.stretched_by();
#endif
  for (std::uint32_t i = begin; i < end; ++i) {
    double vx = vel_x[i], vy = vel_y[i];
    if (const std::uint8_t held = driven[i]; held != 0) {
      if (held & kDriveX) vx = drive_x[i];
      if (held & kDriveY) vy = drive_y[i];
    }
    if constexpr (kDynamic) {
      vx += gravity.x * gravity_scale[i] * dt;
      vy += gravity.y * gravity_scale[i] * dt;
      if constexpr (kKeepVelocities) pre[i] = {vx, vy};
    }
    vel_x[i] = vx;
    vel_y[i] = vy;
    Bodies::Box& box = boxes[i];
#if defined(__SSE2__)
    // x and y as the two lanes of one register, each lane the scalar form's operations (below)
    // on the same operands, so the same bits: ten instructions a body fewer than the compiler's
    // own vectorisation of the scalar form, which took the distance and the fast test per axis.
    const __m128d c0 = _mm_loadu_pd(box.center);
    const __m128d c1 = _mm_add_pd(c0, _mm_mul_pd(_mm_set_pd(vy, vx), step));
    _mm_storeu_pd(box.center, c1);
    _mm_storeu_pd(&start[i].x, c0);
    // Broadphase::distance(): std::max(dx, dy), which is dx < dy ? dy : dx; maxsd(dy, dx) is
    // dy > dx ? dy : dx, the same value for every pair of operands, NaN included.
    const __m128d filed = _mm_sub_pd(
        _mm_and_pd(_mm_sub_pd(c1, _mm_loadu_pd(&filed_at[i].x)), magnitude),
        // The two floats through an integer load, which may alias them.
        _mm_cvtps_pd(
            _mm_castsi128_ps(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(&stretched_by[i])))));
    const double d = _mm_cvtsd_f64(_mm_max_sd(_mm_unpackhi_pd(filed, filed), filed));
    largest = std::max(largest, d);
    if (d > refile) [[unlikely]]
      far_out[far++] = i;
    if constexpr (kFindFast) {
      const __m128d moved = _mm_and_pd(_mm_sub_pd(c1, c0), magnitude);
      const __m128d limit = _mm_mul_pd(_mm_set1_pd(share), _mm_loadu_pd(box.half));
      if (_mm_movemask_pd(_mm_cmpgt_pd(moved, limit)) != 0) fast_out[count++] = i;
    }
#else
    const double x0 = box.center[0], y0 = box.center[1];
    const double x1 = x0 + vx * dt, y1 = y0 + vy * dt;
    box.center[0] = x1;
    box.center[1] = y1;
    start[i] = {x0, y0};
    // The broadphase is noted once the block is done (note_moves).
    const double d = broadphase.distance(i, x1, y1);
    largest = std::max(largest, d);
    if (d > refile) [[unlikely]]
      far_out[far++] = i;
    if constexpr (kFindFast) {
      const double dx = std::abs(x1 - x0), dy = std::abs(y1 - y0);
      if (dx > share * box.half[0] || dy > share * box.half[1]) fast_out[count++] = i;
    }
#endif
  }
  notes = {count, far, largest};
}

template <bool kFindFast, bool kKeepVelocities>
void Motion::integrate_all(Bodies& b, Broadphase& broadphase, Vec2 gravity, double dt,
                           WorkerPool& pool, const std::span<const SlotRun>* only) {
  const std::uint32_t dynamic_end = b.dynamic_end, movable_end = b.movable_end;
  if (far_.size() < movable_end) resize_buffer(far_, movable_end);
  if (only != nullptr) {
    // Run by run in slot order into one list: the notes of one block over the runs' slots.
    Notes notes;
    for (const SlotRun& r : *only) {
      const std::uint32_t split = std::clamp(dynamic_end, r.begin, r.end);
      integrate_range<true, kFindFast, kKeepVelocities>(b, broadphase, gravity, dt, r.begin, split,
                                                        0, notes);
      integrate_range<false, kFindFast, kKeepVelocities>(b, broadphase, gravity, dt, split, r.end,
                                                         0, notes);
    }
    fast_count_ = notes.fast;
    broadphase.note_moves(b, notes.largest, {far_.data(), notes.far});
    return;
  }
  if (pool.threads() == 1 || movable_end <= kBlock) {
    // One block: the moves are noted once it is done, as with workers. Noted body by body, the
    // broadphase's margin was loaded and stored again for every body (the loop's stores of
    // doubles may alias it).
    Notes notes;
    integrate_range<true, kFindFast, kKeepVelocities>(b, broadphase, gravity, dt, 0, dynamic_end, 0,
                                                      notes);
    integrate_range<false, kFindFast, kKeepVelocities>(b, broadphase, gravity, dt, dynamic_end,
                                                       movable_end, 0, notes);
    fast_count_ = notes.fast;
    broadphase.note_moves(b, notes.largest, {far_.data(), notes.far});
    return;
  }
  const std::uint32_t blocks = (movable_end + kBlock - 1) / kBlock;
  if (notes_.size() < blocks) notes_.resize(blocks);
  pool.run(blocks, [&](std::uint32_t k) {
    const std::uint32_t begin = k * kBlock, end = std::min(movable_end, begin + kBlock);
    Notes& notes = notes_[k];
    notes = Notes{};
    const std::uint32_t split = std::clamp(dynamic_end, begin, end);
    integrate_range<true, kFindFast, kKeepVelocities>(b, broadphase, gravity, dt, begin, split,
                                                      begin, notes);
    integrate_range<false, kFindFast, kKeepVelocities>(b, broadphase, gravity, dt, split, end,
                                                       begin, notes);
  });
  // Each block's lists, moved down to follow the blocks before it: slot order, as one thread.
  double largest = 0.0;
  std::uint32_t fast = 0, far = 0;
  for (std::uint32_t k = 0; k < blocks; ++k) {
    const Notes& notes = notes_[k];
    const std::uint32_t begin = k * kBlock;
    std::copy_n(fast_.begin() + begin, notes.fast, fast_.begin() + fast);
    std::copy_n(far_.begin() + begin, notes.far, far_.begin() + far);
    fast += notes.fast;
    far += notes.far;
    largest = std::max(largest, notes.largest);
  }
  fast_count_ = fast;
  broadphase.note_moves(b, largest, {far_.data(), far});
}

void Motion::integrate(Bodies& b, Broadphase& broadphase, Vec2 gravity, double dt, bool find_fast,
                       bool keep_velocities, WorkerPool& pool,
                       const std::span<const SlotRun>* only) {
  fast_count_ = 0;
  if (fast_.size() < b.movable_end) resize_buffer(fast_, b.movable_end);
  if (keep_velocities && pre_velocity.size() < b.dynamic_end)
    resize_buffer(pre_velocity, b.dynamic_end);
  if (find_fast) {
    if (keep_velocities) {
      integrate_all<true, true>(b, broadphase, gravity, dt, pool, only);
    } else {
      integrate_all<true, false>(b, broadphase, gravity, dt, pool, only);
    }
  } else if (keep_velocities) {
    integrate_all<false, true>(b, broadphase, gravity, dt, pool, only);
  } else {
    integrate_all<false, false>(b, broadphase, gravity, dt, pool, only);
  }
}

}  // namespace chain::detail
