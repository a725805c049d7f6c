// SPDX-License-Identifier: MIT
// What a resolver works on during one step, and the moves every resolver makes the same way.
#pragma once

#include "bodies.h"
#include "broadphase.h"
#include "motion.h"
#include "reach.h"
#include "stage_clock.h"
#include "velocity_response.h"
#include "worker_pool.h"

#include <chain/types.h>
#include <chain/world.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace chain::detail {

inline constexpr int kAnyAxis = 2;

// How deep, as a share of what push-out can undo, a body may come to be in another before
// push-out resolves the pair: push-out separates two boxes along their axis of least overlap, away
// from each other's centre, so it sends a body back the way it came only while that body has not
// crossed the other's centre and is less deep along the axis it came in on than across it. The
// share keeps clear of both edges, so rounding never decides. Continuous collision stops fast
// bodies there (continuous.h), and the modern resolver's moves stop there too (StepContext::move).
inline constexpr double kPushOutShare = 0.9;
// The share of a body's half extent it may move unguarded (StepContext::guarded).
inline constexpr double kFreeMoveShare = 1.0 - kPushOutShare;
// A gathering of the bodies overlapping one (ChainState::gather_overlaps: for a resolution, a
// pass's contacts, a crush) that finds this many costs the budget one pair resolution more for
// each such many (StepContext::charge_met). The budget bounds the resolutions, but in a pile
// created all in one place each one meets every body of the pile, and a step would cost the
// budget times the pile's size; only a body carrying or overlapping this many others is charged.
// Such a pile then comes apart over more steps, each bounded (tests/solver/chain_work_test.cpp).
// The move guard's queries are not charged: a guarded move follows a gathering, so the charged
// budget bounds them too.
inline constexpr std::size_t kMetPerResolution = 32;

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
  // Modern: no move takes a body past the centre of a body in its way (see limit_move).
  bool guard_moves;
  WorkerPool& pool;   // for the parts of the step that split into independent blocks
  StageClock& clock;  // laps the resolver's stages into `profile` when profiling
  StepProfile& profile;
  double dt;  // the step's, s
  // Kept when resting islands may be skipped (islands.h): where each body went, what each body's
  // chains spent of the budget, and the bodies this step leaves out (nullptr: none).
  Reach* reach = nullptr;
  std::uint32_t* spent = nullptr;
  const std::uint8_t* skipped = nullptr;

  void noted(std::uint32_t i) {
    broadphase.note_move(i, bodies.x(i), bodies.y(i));
    if (reach != nullptr) reach->note(i, bodies.x(i), bodies.y(i));
  }

  double* vel(int axis) { return axis == 0 ? bodies.vx.data() : bodies.vy.data(); }

  // Takes what a gathering for body i that found `met` bodies costs from the budget: nothing
  // below kMetPerResolution; spent by i's island, as a resolution is (islands.h). A charge the
  // budget cannot meet cuts the step as a resolution it cannot meet does (a budget hit), so that
  // a step is cut exactly when all it asks exceeds the budget, in whatever order it asks.
  void charge_met(std::uint32_t i, std::size_t met) {
    if (met < kMetPerResolution) [[likely]]
      return;
    std::uint64_t units = met / kMetPerResolution;
    if (units > budget) {
      units = budget;
      ++stats.budget_hits;
    }
    budget -= units;
    if (spent != nullptr) spent[i] += static_cast<std::uint32_t>(units);
  }

  // Moves body i by d along axis, or less when guarded (limit_move); returns how far it moved.
  // Under the zero rule, a velocity component that points against the move stops, as the 2014
  // engine's updateTransform did.
  double move(std::uint32_t i, int axis, double d, std::uint32_t follower = kNoSlot) {
    if (guarded(i, axis, d)) d = limit_move(i, axis, d, follower, nullptr, nullptr);
    bodies.pos(axis, i) += d;
    noted(i);
    if (def.velocity_rule == VelocityRule::kZero && d * vel(axis)[i] < 0.0) vel(axis)[i] = 0.0;
    return d;
  }

  // Puts body i at `target` along axis, or short of it when guarded (and `guard`); returns how far
  // it moved.
  // Bodies for which passes(arg, c) is true do not stop a guarded move (a chain's own walls).
  using Passes = bool (*)(const void* arg, std::uint32_t c);

  double place(std::uint32_t i, int axis, double target, std::uint32_t follower = kNoSlot,
               bool guard = true, Passes passes = nullptr, const void* arg = nullptr) {
    double d = target - bodies.pos(axis, i);
    if (guard && guarded(i, axis, d) &&
        (d = limit_move(i, axis, d, follower, passes, arg)) != target - bodies.pos(axis, i)) {
      bodies.pos(axis, i) += d;
    } else {
      bodies.pos(axis, i) = target;  // exactly: resting stacks rebuild the same positions
    }
    noted(i);
    if (def.velocity_rule == VelocityRule::kZero && d * vel(axis)[i] < 0.0) vel(axis)[i] = 0.0;
    return d;
  }

  // Puts body i at `target` along axis, unguarded: for placements that are a squeeze's answer,
  // where every body of a row overlaps its neighbours by design.
  void set(std::uint32_t i, int axis, double target) {
    const double d = target - bodies.pos(axis, i);
    bodies.pos(axis, i) = target;
    noted(i);
    if (def.velocity_rule == VelocityRule::kZero && d * vel(axis)[i] < 0.0) vel(axis)[i] = 0.0;
  }

  // A push moves a body at once by up to an overlap depth, through whatever lies in between: a
  // body pushed out of one it was created deep inside, or followed back along a chain, could cross
  // a third body entirely, or past its centre, where push-out then sends it on through. So the
  // move of body i by d along axis stops where i would be deeper in a body ahead of it than
  // kPushOutShare of the way to its centre: push-out or the chain then resolves that pair the
  // right way round. Bodies that overlap i across the move by less than half the smaller box are
  // grazed, not passed through, and do not stop it; nor do bodies i is already deeper in than
  // half the way from that depth to the centre (only creation leaves a pair so deep, and stopping
  // there would leave it stuck). A static or kinematic body that i was outside of along the move
  // when the step began stops it only before it would come out beyond: push-out takes i back out
  // through the face it came in by at any depth (entry_face.h). `follower` (if any) is about to
  // move after i by as much (a chain's follow-back) and does not stop it. Returns the move
  // allowed, of d's sign and at most |d|.
  double limit_move(std::uint32_t i, int axis, double d, std::uint32_t follower, Passes passes,
                    const void* arg) const;

 private:
  // A move of body i shorter than kFreeMoveShare of its own half extent along the move cannot
  // take it from kPushOutShare of the way to another body's centre past that centre (from there
  // the centre is (1 - kPushOutShare) * (both half extents) ahead, at least this far): only longer
  // moves are checked. Per body, so that a thin shelf elsewhere in the world does not send every
  // resting contact's move through the broadphase.
  bool guarded(std::uint32_t i, int axis, double d) const {
    return guard_moves && std::abs(d) > kFreeMoveShare * bodies.half(axis, i);
  }

 public:
  // Records that `a` was pushed out of `b` along axis, in direction sign (+1 or -1).
  void note_push(std::uint32_t a, std::uint32_t b, int axis, double sign) {
    const std::uint8_t a_side = axis == 0 ? (sign > 0 ? touching::kLeft : touching::kRight)
                                          : (sign > 0 ? touching::kBottom : touching::kTop);
    const std::uint8_t b_side = axis == 0 ? (sign > 0 ? touching::kRight : touching::kLeft)
                                          : (sign > 0 ? touching::kTop : touching::kBottom);
    add_touch(bodies.touching[a], a_side);
    add_touch(bodies.touching[b], b_side);
    if (reach != nullptr && b >= bodies.movable_end) reach->touch(a, b, b_side);
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
