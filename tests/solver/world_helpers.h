// SPDX-License-Identifier: MIT
// Small builders shared by the solver tests: boxes, floors and rows in a few lines.
#pragma once

#include <chain/world.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <vector>

namespace chain::testing {

inline BodyDef dynamic_box(double x, double y, double half = 0.5, double mass = 1.0) {
  BodyDef d;
  d.type = BodyType::kDynamic;
  d.center = {x, y};
  d.half_extents = {half, half};
  d.mass = mass;
  return d;
}

inline BodyDef static_box(double x, double y, double hx, double hy) {
  BodyDef d;
  d.type = BodyType::kStatic;
  d.center = {x, y};
  d.half_extents = {hx, hy};
  return d;
}

inline BodyDef kinematic_box(double x, double y, double hx, double hy, Vec2 velocity) {
  BodyDef d = static_box(x, y, hx, hy);
  d.type = BodyType::kKinematic;
  d.velocity = velocity;
  return d;
}

// A static floor whose top face is y = 0.
inline BodyId add_floor(World& w, double half_width = 50.0) {
  return w.create_body(static_box(0.0, -1.0, half_width, 1.0));
}

inline WorldDef world_def(Variant variant, VelocityRule rule, Vec2 gravity = {0.0, -10.0}) {
  WorldDef d;
  d.variant = variant;
  d.velocity_rule = rule;
  d.gravity = gravity;
  return d;
}

// Depth of the deepest overlap between any two bodies (brute force; tests only).
inline double max_penetration(const World& w, const std::vector<BodyId>& ids,
                              const std::vector<Vec2>& half) {
  double deepest = 0.0;
  for (std::size_t i = 0; i < ids.size(); ++i) {
    for (std::size_t j = i + 1; j < ids.size(); ++j) {
      const Vec2 a = w.position(ids[i]), b = w.position(ids[j]);
      const double ox = half[i].x + half[j].x - std::abs(a.x - b.x);
      const double oy = half[i].y + half[j].y - std::abs(a.y - b.y);
      if (ox > 0.0 && oy > 0.0) deepest = std::max(deepest, std::min(ox, oy));
    }
  }
  return deepest;
}

// A double's bits, for tests that compare results exactly (+0 and -0, NaN payloads apart).
inline std::uint64_t bits(double v) {
  return std::bit_cast<std::uint64_t>(v);
}

// Bodies of ids 0 .. count - 1 whose centre or velocity differ in any bit between two worlds.
inline std::size_t bodies_apart(const World& a, const World& b, std::uint32_t count) {
  std::size_t apart = 0;
  for (std::uint32_t i = 0; i < count; ++i) {
    const BodyId id{i};
    const Vec2 p = a.position(id), q = b.position(id), u = a.velocity(id), v = b.velocity(id);
    if (bits(p.x) != bits(q.x) || bits(p.y) != bits(q.y) || bits(u.x) != bits(v.x) ||
        bits(u.y) != bits(v.y))
      ++apart;
  }
  return apart;
}

inline const char* variant_name(Variant v) {
  return v == Variant::kModern ? "modern" : "seed2014";
}

}  // namespace chain::testing
