// SPDX-License-Identifier: MIT
#include "validate.h"

#include <chain/world.h>

#include <cmath>
#include <cstdio>

namespace chain {
namespace detail {

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

std::string check_range(const char* field, double v, double lo, double hi, const char* what) {
  if (!std::isfinite(v)) return std::string(field) + " must be a finite number, got " + number(v);
  if (v < lo || v > hi) return std::string(field) + " must be " + what + ", got " + number(v);
  return {};
}

}  // namespace detail

using detail::check_range;
using detail::number;

std::string validate(const BodyDef& def) {
  const bool dynamic = def.type == BodyType::kDynamic;
  if (def.type != BodyType::kStatic && def.type != BodyType::kKinematic && !dynamic) {
    return "type must be static, kinematic or dynamic";
  }
  for (const std::string& e :
       {check_range("center.x", def.center.x, -kMaxCoordinate, kMaxCoordinate, "within +-1e9 m"),
        check_range("center.y", def.center.y, -kMaxCoordinate, kMaxCoordinate, "within +-1e9 m"),
        check_range("half_extents.x", def.half_extents.x, 0.0, kMaxHalfExtent, "> 0 and <= 1e8 m"),
        check_range("half_extents.y", def.half_extents.y, 0.0, kMaxHalfExtent, "> 0 and <= 1e8 m"),
        check_range("velocity.x", def.velocity.x, -kMaxSpeed, kMaxSpeed, "within +-1e6 m/s"),
        check_range("velocity.y", def.velocity.y, -kMaxSpeed, kMaxSpeed, "within +-1e6 m/s"),
        check_range("restitution", def.restitution, 0.0, 1.0, "in [0, 1]"),
        check_range("friction", def.friction, 0.0, kMaxFriction, "in [0, 1e6]"),
        check_range("surface_velocity.x", def.surface_velocity.x, -kMaxSpeed, kMaxSpeed,
                    "within +-1e6 m/s"),
        check_range("surface_velocity.y", def.surface_velocity.y, -kMaxSpeed, kMaxSpeed,
                    "within +-1e6 m/s")}) {
    if (!e.empty()) return e;
  }
  if (def.half_extents.x <= 0.0)
    return "half_extents.x must be > 0, got " + number(def.half_extents.x);
  if (def.half_extents.y <= 0.0)
    return "half_extents.y must be > 0, got " + number(def.half_extents.y);
  if (def.type == BodyType::kStatic && (def.velocity.x != 0.0 || def.velocity.y != 0.0)) {
    return "velocity must be zero for a static body (make it kinematic to move it)";
  }
  if (dynamic && (def.surface_velocity.x != 0.0 || def.surface_velocity.y != 0.0)) {
    return "surface_velocity is for static and kinematic bodies (conveyors), must be zero for a "
           "dynamic body";
  }
  if (dynamic) {
    if (!std::isfinite(def.mass) || def.mass <= 0.0 || def.mass > kMaxMass) {
      return "mass must be > 0 and <= 1e18 kg for a dynamic body, got " + number(def.mass);
    }
    std::string e = check_range("gravity_scale", def.gravity_scale, -1.0e6, 1.0e6, "within +-1e6");
    if (!e.empty()) return e;
  }
  return {};
}

std::string validate(const WorldDef& def) {
  if (def.variant != Variant::kModern && def.variant != Variant::kSeed2014) {
    return "variant must be modern or seed2014";
  }
  if (def.velocity_rule != VelocityRule::kZero && def.velocity_rule != VelocityRule::kInelastic) {
    return "velocity_rule must be zero or inelastic";
  }
  for (const auto& e :
       {check_range("gravity.x", def.gravity.x, -kMaxGravity, kMaxGravity, "within +-1e6 m/s^2"),
        check_range("gravity.y", def.gravity.y, -kMaxGravity, kMaxGravity, "within +-1e6 m/s^2"),
        check_range("touch_tolerance", def.touch_tolerance, 0.0, 1.0, "in [0, 1] m"),
        check_range("restitution_threshold", def.restitution_threshold, 0.0, 1.0e6,
                    "in [0, 1e6] m/s")}) {
    if (!e.empty()) return e;
  }
  if (def.max_passes < 1 || def.max_passes > 1000) {
    return "max_passes must be in [1, 1000], got " + std::to_string(def.max_passes);
  }
  if (def.threads < 1 || def.threads > kMaxThreads) {
    return "threads must be in [1, 256], got " + std::to_string(def.threads);
  }
  if (def.budget_per_body < 1 || def.budget_per_body > 1000000) {
    return "budget_per_body must be in [1, 1000000], got " + std::to_string(def.budget_per_body);
  }
  // Each level is a native stack frame; deeper than this risks the thread's stack.
  if (def.seed_max_depth < 1 || def.seed_max_depth > 16384) {
    return "seed_max_depth must be in [1, 16384], got " + std::to_string(def.seed_max_depth);
  }
  return {};
}

}  // namespace chain
