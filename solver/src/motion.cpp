#include "motion.h"

#include <algorithm>
#include <cmath>

namespace chain::detail {

// The one loop every step runs over every body. Array pointers are held in locals and every value
// is read once and written once: the arrays are separate vectors, which the compiler must assume
// may alias each other and the vectors' own bookkeeping, so anything else reloads them all on
// every body.
template <bool kDynamic, bool kFindFast, bool kKeepVelocities>
void Motion::integrate_range(Bodies& b, Broadphase& broadphase, Vec2 gravity, double dt,
                             std::uint32_t begin, std::uint32_t end) {
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
  std::uint32_t* const fast_out = fast_.data();
  std::size_t count = fast_count_;
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
    const double x0 = box.center[0], y0 = box.center[1];
    const double x1 = x0 + vx * dt, y1 = y0 + vy * dt;
    box.center[0] = x1;
    box.center[1] = y1;
    start[i] = {x0, y0};
    broadphase.note_move(i, x1, y1);
    if constexpr (kFindFast) {
      const double dx = std::abs(x1 - x0), dy = std::abs(y1 - y0);
      if (dx > share * box.half[0] || dy > share * box.half[1]) fast_out[count++] = i;
    }
  }
  fast_count_ = count;
}

template <bool kFindFast, bool kKeepVelocities>
void Motion::integrate_all(Bodies& b, Broadphase& broadphase, Vec2 gravity, double dt) {
  integrate_range<true, kFindFast, kKeepVelocities>(b, broadphase, gravity, dt, 0, b.dynamic_end);
  integrate_range<false, kFindFast, kKeepVelocities>(b, broadphase, gravity, dt, b.dynamic_end,
                                                     b.movable_end);
}

void Motion::integrate(Bodies& b, Broadphase& broadphase, Vec2 gravity, double dt, bool find_fast,
                       bool keep_velocities) {
  fast_count_ = 0;
  if (fast_.size() < b.movable_end) fast_.resize(b.movable_end);
  if (keep_velocities && pre_velocity.size() < b.dynamic_end) pre_velocity.resize(b.dynamic_end);
  if (find_fast) {
    if (keep_velocities) {
      integrate_all<true, true>(b, broadphase, gravity, dt);
    } else {
      integrate_all<true, false>(b, broadphase, gravity, dt);
    }
  } else if (keep_velocities) {
    integrate_all<false, true>(b, broadphase, gravity, dt);
  } else {
    integrate_all<false, false>(b, broadphase, gravity, dt);
  }
}

}  // namespace chain::detail
