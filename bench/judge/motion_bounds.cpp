// SPDX-License-Identifier: MIT
#include "judge/motion_bounds.h"

#include "index/box_grid.h"
#include "index/pair_scan.h"
#include "judge/metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace chainbench {
namespace {

std::size_t root(std::vector<std::size_t>& parent, std::size_t i) {
  while (parent[i] != i)
    i = parent[i] = parent[parent[i]];
  return i;
}

}  // namespace

Floor find_floor(const Scene& scene, double sideways, double lift, double sunk) {
  const std::size_t n = scene.bodies.size();
  const double inf = std::numeric_limits<double>::infinity();
  Floor none;
  none.height.assign(n, inf);
  // Gravity along one axis, boxes that keep their orientation: the only scenes whose floor is a
  // face all the way across.
  const bool along_x = scene.gravity.y == 0.0, along_y = scene.gravity.x == 0.0;
  if (scene.rotation || along_x == along_y) return none;
  const int axis = along_y ? 1 : 0;  // the axis gravity is along
  const double down = (along_y ? scene.gravity.y : scene.gravity.x) < 0.0 ? -1.0 : 1.0;
  auto depth = [&](Vec2d p) { return down * (axis == 1 ? p.y : p.x); };  // grows downwards
  auto across = [&](Vec2d p) { return axis == 1 ? p.x : p.y; };
  auto half_depth = [&](const SceneBody& b) {
    return axis == 1 ? b.half_extents.y : b.half_extents.x;
  };
  auto half_across = [&](const SceneBody& b) {
    return axis == 1 ? b.half_extents.x : b.half_extents.y;
  };
  // The dynamic bodies' extent: the deepest bottom, and how far across they reach.
  double bottom = -inf, lo = inf, hi = -inf;
  bool any = false;
  for (const SceneBody& b : scene.bodies) {
    if (b.kind != BodyKind::kDynamic) continue;
    if (b.gravity_scale < 0.0) return none;  // falls upwards: no floor catches it
    any = true;
    bottom = std::max(bottom, depth(b.center) + half_depth(b));
    lo = std::min(lo, across(b.center) - half_across(b));
    hi = std::max(hi, across(b.center) + half_across(b));
  }
  if (!any) return none;
  // The highest floor: a static box under every dynamic one, colliding with each of them, that
  // reaches past them on both sides by more than any of them can travel sideways in the run.
  std::vector<std::pair<std::uint16_t, std::uint16_t>> filters;  // the dynamic bodies' kinds
  if (scene.filters()) {
    for (const SceneBody& b : scene.bodies)
      if (b.kind == BodyKind::kDynamic) filters.emplace_back(b.category_bits, b.mask_bits);
    std::sort(filters.begin(), filters.end());
    filters.erase(std::unique(filters.begin(), filters.end()), filters.end());
  }
  auto catches_all = [&](const SceneBody& f) {
    return std::all_of(filters.begin(), filters.end(), [&](const auto& b) {
      return (f.category_bits & b.second) != 0 && (b.first & f.mask_bits) != 0;
    });
  };
  double ground = inf;
  const double rounding = 1e-9 * (1.0 + std::abs(bottom));
  for (const SceneBody& f : scene.bodies) {
    if (f.kind != BodyKind::kStatic) continue;
    if (f.from_step > 0 || f.to_step < scene.steps) continue;  // not there the whole run
    if (!catches_all(f)) continue;                             // some body passes through it
    const double top = depth(f.center) - half_depth(f);
    if (top < bottom - sunk - rounding || top >= ground) continue;
    if (across(f.center) - half_across(f) > lo - sideways ||
        across(f.center) + half_across(f) < hi + sideways)
      continue;
    ground = top;
  }
  if (!std::isfinite(ground)) return none;
  Floor f;
  f.axis = axis;
  f.down = down;
  f.top = ground;
  f.height.assign(n, inf);
  for (std::size_t i = 0; i < n; ++i) {
    const SceneBody& b = scene.bodies[i];
    if (b.kind != BodyKind::kDynamic) continue;
    f.height[i] = std::max(0.0, ground - (depth(b.center) + half_depth(b))) + sunk + lift;
  }
  return f;
}

MotionBounds motion_bounds(const Scene& scene) {
  const std::size_t n = scene.bodies.size();
  const double inf = std::numeric_limits<double>::infinity();
  const double g = std::hypot(scene.gravity.x, scene.gravity.y);
  const double duration = scene.dt * scene.steps;
  MotionBounds m;
  m.speed.assign(n, 0.0);
  m.reach.assign(n, 0.0);
  m.allowance.assign(n, 0.0);
  m.initial_depth.assign(n, 0.0);

  double fastest = 0.0, drive = 0.0, lift = 0.0, restitution = scene.restitution;
  double largest = 0.0, smallest = inf;
  bool pumped = !scene.drivers.empty();  // drives and moving kinematic bodies do work
  // Speeds against gravity: what can carry a body higher than it starts.
  const Vec2d up = g > 0.0 ? Vec2d{-scene.gravity.x / g, -scene.gravity.y / g} : Vec2d{};
  auto rise = [&](Vec2d v) { return std::max(0.0, v.x * up.x + v.y * up.y); };
  for (const SceneBody& b : scene.bodies) {
    const double speed = std::hypot(b.velocity.x, b.velocity.y);
    restitution = std::max(restitution, scene.restitution_of(b));
    if (b.kind == BodyKind::kKinematic) {
      drive = std::max(drive, speed);
      lift = std::max(lift, rise(b.velocity));
      pumped = pumped || speed > 0.0;
    }
    if (b.kind != BodyKind::kDynamic) {
      // A conveyor's belt drags what touches it up to its own speed on top of its body's.
      const double belt = std::hypot(b.surface_velocity.x, b.surface_velocity.y);
      drive = std::max(drive, speed + belt);
      lift = std::max(
          lift, rise({b.velocity.x + b.surface_velocity.x, b.velocity.y + b.surface_velocity.y}));
      pumped = pumped || belt > 0.0;
    }
    if (b.kind != BodyKind::kDynamic) continue;
    fastest = std::max(fastest, speed);
    largest = std::max(largest, std::hypot(b.half_extents.x, b.half_extents.y));
    smallest = std::min({smallest, 2.0 * b.half_extents.x, 2.0 * b.half_extents.y});
  }
  for (const Driver& d : scene.drivers) {
    drive = std::max(drive, std::hypot(d.velocity.x, d.velocity.y));
    lift = std::max(lift, rise(d.velocity));
  }
  if (restitution > 0.0 && pumped) {
    m.unbounded = "bounces off driven or moving kinematic bodies can gain energy without limit";
  }

  // Clusters of bodies overlapping or touching at the start, and the overlaps each holds.
  std::vector<std::size_t> parent(n);
  std::iota(parent.begin(), parent.end(), std::size_t{0});
  std::vector<double> cluster_overlap(n, 0.0);
  {
    const BodyState start = initial_state(scene);
    PairScan scan(scene);
    scan.build(start, start);
    std::vector<std::pair<std::size_t, std::size_t>> touching;
    scan.for_each_pair([&](std::size_t i, std::size_t j) {
      // Bodies that come and go start together only if they enter together: a body entering
      // later meets the others wherever they are then, and a body leaving early never meets one
      // entering after it.
      if (scene.bodies[i].from_step != scene.bodies[j].from_step) return;
      touching.emplace_back(i, j);
      const double d = scan.depth(start, i, j);
      if (d <= 0.0) return;
      m.initial_overlaps.push_back({pair_key(i, j), d});
      m.initial_depth[i] = std::max(m.initial_depth[i], d);
      m.initial_depth[j] = std::max(m.initial_depth[j], d);
    });
    // Immovable bodies do not join clusters: a floor would make one of a whole scene.
    for (const auto& [i, j] : touching) {
      if (scene.bodies[i].kind == BodyKind::kDynamic && scene.bodies[j].kind == BodyKind::kDynamic)
        parent[root(parent, i)] = root(parent, j);
    }
    std::sort(m.initial_overlaps.begin(), m.initial_overlaps.end());
    for (const auto& [key, depth] : m.initial_overlaps) {
      const auto i = static_cast<std::size_t>(key >> 32),
                 j = static_cast<std::size_t>(key & 0xffffffffu);
      const std::size_t body = scene.bodies[i].kind == BodyKind::kDynamic ? i : j;
      cluster_overlap[root(parent, body)] += depth;
    }
  }
  // Pushing a cluster's overlaps apart moves its bodies by up to those overlaps, and with them any
  // body within that reach of the cluster: each body may travel as far as the largest overlap of
  // any cluster whose box, grown by that overlap, reaches it.
  using Box = BoxGrid::Box;
  auto box_of = [&](std::size_t i) {
    const SceneBody& b = scene.bodies[i];
    return Box{b.center.x - b.half_extents.x, b.center.y - b.half_extents.y,
               b.center.x + b.half_extents.x, b.center.y + b.half_extents.y};
  };
  std::vector<Box> cluster_box(n, Box{inf, inf, -inf, -inf});
  std::vector<std::size_t> dynamic;
  std::vector<Box> boxes;
  std::vector<double> sizes;
  for (std::size_t i = 0; i < n; ++i) {
    if (scene.bodies[i].kind != BodyKind::kDynamic) continue;
    Box& c = cluster_box[root(parent, i)];
    const Box b = box_of(i);
    c = {std::min(c.x0, b.x0), std::min(c.y0, b.y0), std::max(c.x1, b.x1), std::max(c.y1, b.y1)};
    dynamic.push_back(i);
    boxes.push_back(b);
    sizes.push_back(std::max(b.x1 - b.x0, b.y1 - b.y0));
  }
  // A grid of the dynamic bodies, its cells about the size of most of them, so that each cluster
  // finds the bodies its reach touches without walking past the rest.
  double cell = 1.0;
  if (!sizes.empty()) {
    const auto k = static_cast<std::ptrdiff_t>((sizes.size() - 1) * 9 / 10);
    std::nth_element(sizes.begin(), sizes.begin() + k, sizes.end());
    cell = sizes[static_cast<std::size_t>(k)];
  }
  const BoxGrid grid(boxes, cell);
  std::vector<double> pushed(n, 0.0);
  for (std::size_t c = 0; c < n; ++c) {
    const double s = cluster_overlap[c];
    if (s <= 0.0) continue;
    const Box reach{cluster_box[c].x0 - s, cluster_box[c].y0 - s, cluster_box[c].x1 + s,
                    cluster_box[c].y1 + s};
    grid.for_each_touching(
        reach, [&](std::size_t k) { pushed[dynamic[k]] = std::max(pushed[dynamic[k]], s); });
  }

  // What gravity can give each body: the fall from its height above the floor when the scene
  // has one it cannot leave (find_floor), else a fall lasting the whole run. With bounces a body
  // may be thrown sideways faster than anything moves: no floor is wide enough to be sure of.
  double pushes = 0.0;
  for (const auto& overlap : m.initial_overlaps)
    pushes += overlap.second;
  const double sideways =
      restitution > 0.0 ? inf : (fastest + drive) * duration + pushes + 2.0 * largest;
  m.floor = find_floor(scene, sideways, lift * duration, pushes);
  double floor_fall = 0.0, run_fall = 0.0, energy = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const SceneBody& b = scene.bodies[i];
    if (b.kind != BodyKind::kDynamic) continue;
    const double pull = g * std::abs(b.gravity_scale);
    double fall = pull * duration;
    run_fall = std::max(run_fall, fall);
    if (std::isfinite(m.floor.height[i]))
      fall = std::min(fall, std::sqrt(2.0 * pull * m.floor.height[i]));
    floor_fall = std::max(floor_fall, fall);
    const double own = std::hypot(b.velocity.x, b.velocity.y) + fall;
    energy += 0.5 * b.mass * own * own;
  }

  // No bounce: nothing leaves a collision faster than the fastest thing in it.
  const double bounded_speed = fastest + floor_fall + drive;
  const double fallen_speed = 1.25 * (fastest + run_fall + drive) + 1.0;
  m.fallen.assign(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const SceneBody& b = scene.bodies[i];
    if (b.kind != BodyKind::kDynamic) continue;
    double v = bounded_speed;
    if (restitution > 0.0)
      v = m.unbounded.empty() ? std::max(v, std::sqrt(2.0 * energy / b.mass)) : inf;
    m.speed[i] = 1.25 * v + 1.0;
    m.fallen[i] = std::max(m.speed[i], fallen_speed);
    if (std::isfinite(m.speed[i])) m.largest_speed = std::max(m.largest_speed, m.speed[i]);
    m.allowance[i] = pushed[i] + 0.05 * smallest;
    // Where a body may end: as far as it may go once through the floor (a tunnelling, which is
    // judged as such rather than as an escape).
    m.reach[i] = m.fallen[i] * duration + m.allowance[i] + 2.0 * largest;
  }
  return m;
}

}  // namespace chainbench
