// SPDX-License-Identifier: MIT
// The resolver most people write first, as a chainbench plugin: integrate, then `iterations` times
// over every overlapping pair push the two boxes apart along the axis of least overlap, split by
// mass (immovable bodies take none of it), and stop the velocity that points into the push. No
// chaining: a push that causes a new overlap waits for the next iteration, or the next step.
//
//   chainbench run --scene pyramid --engines chain,plugin:path=./librelaxation.so,iterations=8
#include <chainbench/engine_plugin.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <new>
#include <numeric>
#include <vector>

struct cb_world {
  std::vector<cb_body> bodies;
  std::vector<std::uint32_t> by_left;  // bodies sorted by their left edge, kept between steps
  double gravity[2] = {0, 0};
  double dt = 0;
  int iterations = 4;
  double pushes = 0;  // pair pushes in the last step
};

namespace {

bool movable(const cb_body& b) {
  return b.kind == CB_DYNAMIC;
}

// Every pair of bodies whose boxes overlap, at least one dynamic, by sweeping along x.
template <class Fn>
void each_overlap(cb_world& w, Fn&& fn) {
  auto left = [&](std::uint32_t i) { return w.bodies[i].center[0] - w.bodies[i].half_extents[0]; };
  // Insertion sort: the order barely changes from one pass to the next.
  for (std::size_t k = 1; k < w.by_left.size(); ++k) {
    const std::uint32_t i = w.by_left[k];
    std::size_t m = k;
    for (; m > 0 && left(w.by_left[m - 1]) > left(i); --m)
      w.by_left[m] = w.by_left[m - 1];
    w.by_left[m] = i;
  }
  for (std::size_t k = 0; k < w.by_left.size(); ++k) {
    const cb_body& a = w.bodies[w.by_left[k]];
    const double right = a.center[0] + a.half_extents[0];
    for (std::size_t m = k + 1; m < w.by_left.size() && left(w.by_left[m]) < right; ++m) {
      const cb_body& b = w.bodies[w.by_left[m]];
      if (!movable(a) && !movable(b)) continue;
      const double ox = a.half_extents[0] + b.half_extents[0] - std::abs(a.center[0] - b.center[0]);
      const double oy = a.half_extents[1] + b.half_extents[1] - std::abs(a.center[1] - b.center[1]);
      if (ox > 0 && oy > 0) fn(w.by_left[k], w.by_left[m], ox, oy);
    }
  }
}

void push_apart(cb_world& w, std::uint32_t i, std::uint32_t j, double ox, double oy) {
  cb_body& a = w.bodies[i];
  cb_body& b = w.bodies[j];
  const int axis = ox <= oy ? 0 : 1;
  const double depth = axis == 0 ? ox : oy;
  const double sign = a.center[axis] >= b.center[axis] ? 1.0 : -1.0;  // a moves this way
  const double ia = movable(a) ? 1.0 / a.mass : 0.0, ib = movable(b) ? 1.0 / b.mass : 0.0;
  const double share = ia / (ia + ib);
  a.center[axis] += sign * depth * share;
  b.center[axis] -= sign * depth * (1.0 - share);
  // Velocity into the push stops.
  if (movable(a) && a.velocity[axis] * sign < 0) a.velocity[axis] = 0;
  if (movable(b) && b.velocity[axis] * sign > 0) b.velocity[axis] = 0;
  w.pushes += 1;
}

cb_world* create(const cb_world_desc* desc, char*, std::size_t) {
  auto* w = new (std::nothrow) cb_world;
  if (!w) return nullptr;
  // chainbench has checked every setting against kKeys and filled in the defaults.
  for (std::uint32_t k = 0; k < desc->setting_count; ++k) {
    if (std::strcmp(desc->settings[k].key, "iterations") == 0)
      w->iterations = std::atoi(desc->settings[k].value);
  }
  w->bodies.assign(desc->bodies, desc->bodies + desc->body_count);
  w->by_left.resize(desc->body_count);
  std::iota(w->by_left.begin(), w->by_left.end(), 0u);
  w->gravity[0] = desc->gravity[0], w->gravity[1] = desc->gravity[1];
  w->dt = desc->dt;
  return w;
}

int set_velocity(cb_world* w, std::uint32_t body, double vx, double vy, std::uint32_t axes) {
  if (body >= w->bodies.size() || w->bodies[body].kind == CB_STATIC) return 1;
  if (axes & CB_AXIS_X) w->bodies[body].velocity[0] = vx;
  if (axes & CB_AXIS_Y) w->bodies[body].velocity[1] = vy;
  return 0;
}

int step(cb_world* w, char*, std::size_t) {
  for (cb_body& b : w->bodies) {
    if (b.kind == CB_STATIC) continue;
    if (movable(b)) {
      b.velocity[0] += w->gravity[0] * b.gravity_scale * w->dt;
      b.velocity[1] += w->gravity[1] * b.gravity_scale * w->dt;
    }
    b.center[0] += b.velocity[0] * w->dt;
    b.center[1] += b.velocity[1] * w->dt;
  }
  w->pushes = 0;
  for (int k = 0; k < w->iterations; ++k) {
    each_overlap(*w, [&](std::uint32_t i, std::uint32_t j, double ox, double oy) {
      push_apart(*w, i, j, ox, oy);
    });
  }
  return 0;
}

std::uint32_t read_state(const cb_world* w, double* positions, double* velocities, double* angles,
                         std::uint32_t capacity) {
  const auto n = static_cast<std::uint32_t>(w->bodies.size());
  for (std::uint32_t i = 0; i < n && i < capacity; ++i) {
    const cb_body& b = w->bodies[i];
    if (positions) positions[2 * i] = b.center[0], positions[2 * i + 1] = b.center[1];
    if (velocities) velocities[2 * i] = b.velocity[0], velocities[2 * i + 1] = b.velocity[1];
    if (angles) angles[i] = 0.0;
  }
  return n;
}

const cb_counter kCounters[] = {{"pushes", "pair pushes in a step", CB_AGG_MEAN}};

void read_counters(const cb_world* w, double* values) {
  values[0] = w->pushes;
}

void destroy(cb_world* w) {
  delete w;
}

// Positional, as C++17 has it: the fields in the order engine_plugin.h declares them.
const cb_key kKeys[] = {
    {"iterations", CB_KEY_INTEGER, 1, 1000, "4", "passes over the overlapping pairs per step"}};

const cb_engine kEngine = {CHAINBENCH_PLUGIN_ABI,
                           sizeof(cb_engine),
                           "relaxation",
                           CB_CAN_KINEMATIC | CB_CAN_AXIS_DRIVES,
                           1,
                           kCounters,
                           1,
                           kKeys,
                           create,
                           set_velocity,
                           step,
                           read_state,
                           read_counters,
                           destroy,
                           nullptr,   // add_body: no CB_CAN_LIFETIMES, so chainbench refuses
                           nullptr};  // scenes whose bodies come and go

}  // namespace

extern "C" CHAINBENCH_PLUGIN_EXPORT const cb_engine* chainbench_engine_plugin(void) {
  return &kEngine;
}
