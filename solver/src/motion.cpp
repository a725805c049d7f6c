#include "motion.h"

#include <algorithm>
#include <cmath>

namespace chain::detail {

void Motion::integrate(Bodies& b, Broadphase& broadphase, Vec2 gravity, double dt, bool find_fast,
                       bool keep_velocities) {
  fast.clear();
  slow_reach = 0.0;
  if (fast.capacity() < b.movable_end) fast.reserve(b.movable_end);
  if (keep_velocities && pre_velocity.size() < b.dynamic_end) pre_velocity.resize(b.dynamic_end);
  for (std::uint32_t i = 0; i < b.movable_end; ++i) {
    if (b.driven[i] & kDriveX) b.vx[i] = b.drive_x[i];
    if (b.driven[i] & kDriveY) b.vy[i] = b.drive_y[i];
    const bool dynamic = i < b.dynamic_end;
    if (dynamic) {
      b.vx[i] += gravity.x * b.gravity_scale[i] * dt;
      b.vy[i] += gravity.y * b.gravity_scale[i] * dt;
      if (keep_velocities) pre_velocity[i] = {b.vx[i], b.vy[i]};
    }
    const double x0 = b.pos(0, i), y0 = b.pos(1, i);
    b.start[i] = {x0, y0};
    b.pos(0, i) += b.vx[i] * dt;
    b.pos(1, i) += b.vy[i] * dt;
    broadphase.note_move(i, b.x(i), b.y(i));
    if (find_fast) {
      const double dx = std::abs(b.x(i) - x0), dy = std::abs(b.y(i) - y0);
      const double share = dynamic ? kFastDynamicShare : kFastKinematicShare;
      if (dx > share * b.hx(i) || dy > share * b.hy(i)) {
        fast.push_back(i);
      } else {
        slow_reach = std::max(slow_reach, std::max(dx, dy));
      }
    }
  }
}

}  // namespace chain::detail
