#include "motion_bounds.h"

#include "box_grid.h"
#include "metrics.h"
#include "pair_scan.h"

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

  double fastest = 0.0, drive = 0.0, restitution = scene.restitution, energy = 0.0;
  double largest = 0.0, smallest = inf, fall = 0.0;
  bool pumped = !scene.drivers.empty();  // drives and moving kinematic bodies do work
  for (const SceneBody& b : scene.bodies) {
    const double speed = std::hypot(b.velocity.x, b.velocity.y);
    restitution = std::max(restitution, scene.restitution_of(b));
    if (b.kind == BodyKind::kKinematic) {
      drive = std::max(drive, speed);
      pumped = pumped || speed > 0.0;
    }
    if (b.kind != BodyKind::kDynamic) continue;
    const double own = speed + g * std::abs(b.gravity_scale) * duration;
    fastest = std::max(fastest, speed);
    fall = std::max(fall, g * std::abs(b.gravity_scale) * duration);
    energy += 0.5 * b.mass * own * own;
    largest = std::max(largest, std::hypot(b.half_extents.x, b.half_extents.y));
    smallest = std::min({smallest, 2.0 * b.half_extents.x, 2.0 * b.half_extents.y});
  }
  for (const Driver& d : scene.drivers)
    drive = std::max(drive, std::hypot(d.velocity.x, d.velocity.y));
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

  const double bounded_speed = fastest + fall + drive;  // no bounce: the fastest in a collision
  for (std::size_t i = 0; i < n; ++i) {
    const SceneBody& b = scene.bodies[i];
    if (b.kind != BodyKind::kDynamic) continue;
    double v = bounded_speed;
    if (restitution > 0.0)
      v = m.unbounded.empty() ? std::max(v, std::sqrt(2.0 * energy / b.mass)) : inf;
    m.speed[i] = 1.25 * v + 1.0;
    if (std::isfinite(m.speed[i])) m.largest_speed = std::max(m.largest_speed, m.speed[i]);
    m.allowance[i] = pushed[i] + 0.05 * smallest;
    m.reach[i] = m.speed[i] * duration + m.allowance[i] + 2.0 * largest;
  }
  return m;
}

}  // namespace chainbench
