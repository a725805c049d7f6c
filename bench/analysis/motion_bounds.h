// What a scene lets its bodies do: how fast and how far each dynamic body may move, from what
// gravity, drivers, kinematic bodies, initial speeds and bounces can give it, and how far the
// overlaps the scene starts with may push it. The stability verdicts (blow-up, escape) are
// judged against these, per body.
//
// Speed. Without bounces a collision never leaves a body faster than the fastest thing in it, so
// a body moves no faster than its start speed, the fall it can gather over the run and the
// fastest driver or kinematic body. With bounces, energy bounds it instead: a body can end with
// all the kinetic energy every body could gather (its start speed and fall, summed over bodies),
// so a light box tossed by a heavy one may go far faster than either. Bounces off a driven or
// moving kinematic body can pump energy in without limit: such a scene has no speed bound. Each
// bound gets a quarter more, plus 1 m/s.
//
// Overlaps. Bodies that start overlapping are pushed apart, and a push moves a body without
// speed: each body may travel beyond its speed bound by the overlaps of the cluster it starts in
// (bodies overlapping or touching at the start), or of any cluster that reaches it when grown by
// its overlaps, plus 5% of the scene's smallest box.
#pragma once

#include "scene.h"

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace chainbench {

struct MotionBounds {
  std::vector<double> speed;      // per body: the fastest it may move, m/s; infinity: no bound
  std::vector<double> reach;      // per body: the farthest from its start it may end, m
  std::vector<double> allowance;  // per body: how far it may travel beyond its speed bound, m
  // Overlaps at the start, as (i << 32 | j, depth) sorted by pair.
  std::vector<std::pair<std::uint64_t, double>> initial_overlaps;
  std::vector<double> initial_depth;  // per body: its deepest overlap at the start, m
  double largest_speed = 0.0;         // the largest finite per-body bound, m/s
  std::string unbounded;              // why speed is not bounded, when it is not
};

MotionBounds motion_bounds(const Scene& scene);

inline std::uint64_t pair_key(std::size_t i, std::size_t j) {
  return static_cast<std::uint64_t>(i) << 32 | static_cast<std::uint64_t>(j);
}

}  // namespace chainbench
