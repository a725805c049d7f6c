// What a resolver works on during one step, and the moves every resolver makes the same way.
#pragma once

#include "bodies.h"
#include "broadphase.h"
#include "motion.h"
#include "velocity_response.h"

#include <chain/types.h>
#include <chain/world.h>

#include <cmath>
#include <cstdint>
#include <vector>

namespace chain::detail {

inline constexpr int kAnyAxis = 2;

struct CrushRecord {
  std::uint32_t body, anchor, blocker;
  Axis axis;
};

struct StepContext {
  Bodies& bodies;
  Broadphase& broadphase;
  VelocityResponse& response;
  const WorldDef& def;
  StepStats& stats;
  std::vector<CrushRecord>& crushes;
  std::uint64_t budget;  // pair resolutions left this step
  const Motion& motion;  // what integration did this step
  bool record_links;     // pushes are recorded for the inelastic rule or friction

  double* vel(int axis) { return axis == 0 ? bodies.vx.data() : bodies.vy.data(); }

  // Moves body i by d along axis. Under the zero rule, a velocity component that points against
  // the move stops, as the 2014 engine's updateTransform did.
  void move(std::uint32_t i, int axis, double d) {
    bodies.pos(axis, i) += d;
    broadphase.note_move(i, bodies.x(i), bodies.y(i));
    if (def.velocity_rule == VelocityRule::kZero && d * vel(axis)[i] < 0.0) vel(axis)[i] = 0.0;
  }

  // Puts body i at `target` along axis; returns how far it moved.
  double place(std::uint32_t i, int axis, double target) {
    const double d = target - bodies.pos(axis, i);
    bodies.pos(axis, i) = target;
    broadphase.note_move(i, bodies.x(i), bodies.y(i));
    if (def.velocity_rule == VelocityRule::kZero && d * vel(axis)[i] < 0.0) vel(axis)[i] = 0.0;
    return d;
  }

  // Records that `a` was pushed out of `b` along axis, in direction sign (+1 or -1).
  void note_push(std::uint32_t a, std::uint32_t b, int axis, double sign) {
    const std::uint8_t a_side = axis == 0 ? (sign > 0 ? touching::kLeft : touching::kRight)
                                          : (sign > 0 ? touching::kBottom : touching::kTop);
    const std::uint8_t b_side = axis == 0 ? (sign > 0 ? touching::kRight : touching::kLeft)
                                          : (sign > 0 ? touching::kTop : touching::kBottom);
    bodies.touching[a] |= a_side;
    bodies.touching[b] |= b_side;
    if (record_links) response.add(a, b, axis, sign);
  }
};

// Penetration depth of two boxes along each axis; both positive means they overlap.
struct Overlap {
  double x, y;
};

inline Overlap overlap(const Bodies& b, std::uint32_t i, std::uint32_t j) {
  return {(b.hx(i) + b.hx(j)) - std::abs(b.x(i) - b.x(j)),
          (b.hy(i) + b.hy(j)) - std::abs(b.y(i) - b.y(j))};
}

// The axis of least penetration, along which a push separates them; ties go to x, as in 2014.
inline int overlap_axis(const Overlap& o) {
  return o.x <= o.y ? 0 : 1;
}

inline bool overlapping(const Bodies& b, std::uint32_t i, std::uint32_t j, double tolerance) {
  const Overlap o = overlap(b, i, j);
  return o.x > tolerance && o.y > tolerance;
}

}  // namespace chain::detail
