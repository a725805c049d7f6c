// SPDX-License-Identifier: MIT
// What a scene lets its bodies do: how fast and how far each dynamic body may move, from what
// gravity, drivers, kinematic bodies, initial speeds and bounces can give it, and how far the
// overlaps the scene starts with may push it. The stability verdicts (blow-up, escape) are
// judged against these, per body.
//
// Speed. Without bounces a collision never leaves a body faster than the fastest thing in it, so
// a body moves no faster than its start speed, the fall it can gather and the fastest driver or
// kinematic body. The fall is sqrt(2 g h) from the height h a body has above the scene's floor
// (find_floor), plus what kinematic bodies and drives moving against gravity can lift it over
// the run; a scene without such a floor lets a body fall the whole run, g * duration. With bounces,
// energy bounds it instead: a body can end with all the kinetic energy every body could gather (its
// start speed and fall, summed over bodies), so a light box tossed by a heavy one may go far faster
// than either. Bounces off a driven or moving kinematic body can pump energy in without limit: such
// a scene has no speed bound. Each bound gets a quarter more, plus 1 m/s.
//
// Overlaps. Bodies that start overlapping are pushed apart, and a push moves a body without
// speed: each body may travel beyond its speed bound by the overlaps of the cluster it starts in
// (bodies overlapping or touching at the start), or of any cluster that reaches it when grown by
// its overlaps, plus 5% of the scene's smallest box. Where bodies come and go
// (SceneBody::from_step) the overlaps a scene starts with are those of bodies that enter together,
// at the same step, as the scene places them; a floor is a static box in the world for the whole
// run.
#pragma once

#include "model/scene.h"

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace chainbench {

// A floor no body can leave (motion_bounds() says when a scene has one): the axis gravity is
// along (0: x, 1: y; -1: no floor), which way is down along it (-1 or 1) and the floor's top, as
// a depth (the coordinate times `down`: larger is lower).
struct Floor {
  int axis = -1;
  double down = -1.0;
  double top = 0.0;
  std::vector<double> height;  // per body: how far it can fall onto the floor, m (infinity: none)
  // Whether a centre at p is below the floor's top: sunk through it, beyond what it holds.
  bool below(Vec2d p) const { return axis >= 0 && down * (axis == 1 ? p.y : p.x) > top; }
};

struct MotionBounds {
  std::vector<double> speed;  // per body: the fastest it may move, m/s; infinity: no bound
  // Per body: its bound once its centre is below the floor's top (a fall lasting the run, as in a
  // scene without a floor): a body through the floor is tunnelled, not also a blow-up.
  std::vector<double> fallen;
  Floor floor;
  std::vector<double> reach;      // per body: the farthest from its start it may end, m
  std::vector<double> allowance;  // per body: how far it may travel beyond its speed bound, m
  // Overlaps at the start, as (i << 32 | j, depth) sorted by pair.
  std::vector<std::pair<std::uint64_t, double>> initial_overlaps;
  std::vector<double> initial_depth;  // per body: its deepest overlap at the start, m
  double largest_speed = 0.0;         // the largest finite per-body bound, m/s
  std::string unbounded;              // why speed is not bounded, when it is not
};

MotionBounds motion_bounds(const Scene& scene);

// The scene's floor, when it has one no body can leave: gravity along an axis, no rotation, and a
// static box whose top is under every dynamic body (or within `sunk` m above their bottoms:
// overlaps the scene starts with) and reaches `sideways` m past them on both sides (farther than
// anything can carry them across). Each body's height is from its bottom to that floor's top,
// plus `sunk` and `lift` (m that rising drives can carry a body up). No floor (axis -1, every
// height infinite) when there is no such box or a body's gravity scale is negative.
Floor find_floor(const Scene& scene, double sideways, double lift, double sunk);

inline std::uint64_t pair_key(std::size_t i, std::size_t j) {
  return static_cast<std::uint64_t>(i) << 32 | static_cast<std::uint64_t>(j);
}

}  // namespace chainbench
