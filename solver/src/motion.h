// SPDX-License-Identifier: MIT
// Integration: drives, gravity and positions for one step, and what the rest of the step needs
// to know about it: where every movable body started (Bodies::start), which bodies moved far for
// their size (continuous collision takes those), and the velocities before push-out (friction
// weighs contacts by the momentum push-out took).
#pragma once

#include "bodies.h"
#include "broadphase.h"
#include "worker_pool.h"

#include <chain/types.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace chain::detail {

// A dynamic body is fast when a step moves it more than this share of its half extent along an
// axis: two slow dynamic bodies then close by less than half their summed half extents, so their
// centres never cross and least-overlap push-out separates them the right way. A kinematic body
// is fast past its whole half extent: a slow kinematic body and a slow dynamic one close by less
// than their summed half extents, so neither passes through the other, and the face rule
// (entry_face.h) resolves any overlap short of that.
inline constexpr double kFastDynamicShare = 0.5;
inline constexpr double kFastKinematicShare = 1.0;

// The velocity integrate() would give body i this step (drives, then gravity), in the same
// operations.
inline Vec2 integrated_velocity(const Bodies& b, std::uint32_t i, Vec2 gravity, double dt) {
  double vx = b.vx[i], vy = b.vy[i];
  if (const std::uint8_t held = b.driven[i]; held != 0) {
    if (held & kDriveX) vx = b.drive_x[i];
    if (held & kDriveY) vy = b.drive_y[i];
  }
  if (i < b.dynamic_end) {
    vx += gravity.x * b.gravity_scale[i] * dt;
    vy += gravity.y * b.gravity_scale[i] * dt;
  }
  return {vx, vy};
}

// How far integrate() would move body i along its farther axis this step: for a body a step
// leaves out (islands.h), what the step that solves it would have moved it, in the same
// operations.
inline double integrated_move(const Bodies& b, std::uint32_t i, Vec2 gravity, double dt) {
  const Vec2 v = integrated_velocity(b, i, gravity, dt);
  const double x0 = b.box[i].center[0], y0 = b.box[i].center[1];
  const double x1 = x0 + v.x * dt, y1 = y0 + v.y * dt;
  return std::max(std::abs(x1 - x0), std::abs(y1 - y0));
}

// Slots [begin, end): a run of the bodies a step solves.
struct SlotRun {
  std::uint32_t begin, end;
};

struct Motion {
  // Movable slots that moved fast this step, ascending (filled when sweeping is on).
  std::span<const std::uint32_t> fast() const { return {fast_.data(), fast_count_}; }
  // Per dynamic slot, the velocity after drives and gravity (filled when keeping velocities).
  std::vector<Point> pre_velocity;

  // Applies drives and gravity to velocities, moves every movable body by velocity * dt, records
  // start positions (and, as asked, the fast bodies and the velocities), and notes every move.
  // With workers, blocks of kBlock bodies are integrated at once and their notes combined in
  // block order: the same bits as one thread.
  // `only`, when not null: the runs of movable slots to integrate, ascending (a step that leaves
  // resting islands out, islands.h), on one thread; the others keep everything.
  void integrate(Bodies& bodies, Broadphase& broadphase, Vec2 gravity, double dt, bool find_fast,
                 bool keep_velocities, WorkerPool& pool,
                 const std::span<const SlotRun>* only = nullptr);

  static constexpr std::uint32_t kBlock = 2048;

 private:
  // What integrating a block found: fast bodies and bodies to file again, written from the
  // block's first slot on in fast_ and far_ (one thread), and the largest move from a filed place.
  struct Notes {
    std::uint32_t fast = 0, far = 0;
    double largest = 0.0;
  };
  template <bool kDynamic, bool kFindFast, bool kKeepVelocities>
  void integrate_range(Bodies& bodies, Broadphase& broadphase, Vec2 gravity, double dt,
                       std::uint32_t begin, std::uint32_t end, std::uint32_t out, Notes& notes);
  template <bool kFindFast, bool kKeepVelocities>
  void integrate_all(Bodies& bodies, Broadphase& broadphase, Vec2 gravity, double dt,
                     WorkerPool& pool, const std::span<const SlotRun>* only);

  std::vector<std::uint32_t> fast_;  // room for every movable slot; the first fast_count_ count
  std::size_t fast_count_ = 0;
  std::vector<std::uint32_t> far_;  // room for every movable slot
  std::vector<Notes> notes_;        // with workers: per block
};

}  // namespace chain::detail
