#include "motion.h"

namespace chain::detail {

void Motion::integrate(Bodies& b, Broadphase& broadphase, Vec2 gravity, double dt) {
  for (std::uint32_t i = 0; i < b.movable_end; ++i) {
    if (b.driven[i] & kDriveX) b.vx[i] = b.drive_x[i];
    if (b.driven[i] & kDriveY) b.vy[i] = b.drive_y[i];
    if (i < b.dynamic_end) {
      b.vx[i] += gravity.x * b.gravity_scale[i] * dt;
      b.vy[i] += gravity.y * b.gravity_scale[i] * dt;
    }
    b.start[i] = {b.x(i), b.y(i)};
    b.pos(0, i) += b.vx[i] * dt;
    b.pos(1, i) += b.vy[i] * dt;
    broadphase.note_move(i, b.x(i), b.y(i));
  }
}

}  // namespace chain::detail
