// SPDX-License-Identifier: MIT
#include "campaign/shard.h"

#include "judge/metrics.h"
#include "support/fnv1a.h"
#include "support/input_error.h"

#include <charconv>
#include <cstdio>

namespace chainbench {
namespace {

// Exactly, as hexadecimal floating point: two scenes that differ in any bit differ here.
std::string exact(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%a", v);
  return buf;
}

std::string exact(Vec2d v) {
  return exact(v.x) + "," + exact(v.y);
}

std::string optional(const std::optional<double>& v) {
  return v ? exact(*v) : std::string("-");
}

}  // namespace

Shard parse_shard(const std::string& text) {
  const std::size_t slash = text.find('/');
  Shard s;
  auto whole = [&](std::string_view part, int& out) {
    const auto [end, ec] = std::from_chars(part.data(), part.data() + part.size(), out);
    return ec == std::errc() && end == part.data() + part.size();
  };
  if (slash == std::string::npos || !whole(std::string_view(text).substr(0, slash), s.index) ||
      !whole(std::string_view(text).substr(slash + 1), s.count) || s.count < 1 ||
      s.count > 100000 || s.index < 1 || s.index > s.count) {
    throw InputError("--shard " + text +
                     ": expected K/N, the K-th of N parts, 1 <= K <= N <= 100000 (e.g. 2/8)");
  }
  return s;
}

std::string scene_identity(const Scene& s) {
  std::string id = s.name + ";" + exact(s.gravity) + ";" + exact(s.dt) + ";" +
                   std::to_string(s.steps) + ";" + (s.rotation ? "r" : "-") + exact(s.friction) +
                   ";" + exact(s.restitution) + ";" + optional(s.penetration_tolerance);
  for (const SceneBody& b : s.bodies) {
    id += "|" + b.name + ":" + to_string(b.kind) + ":" + exact(b.center) + ":" +
          exact(b.half_extents) + ":" + exact(b.velocity) + ":" + exact(b.mass) + ":" +
          exact(b.gravity_scale) + ":" + optional(b.friction) + ":" + optional(b.restitution) +
          ":" + optional(b.penetration_tolerance);
  }
  for (const Driver& d : s.drivers) {
    id += "|drive " + std::to_string(d.body) + ":" + exact(d.velocity) + ":" +
          std::to_string(d.from_step) + ":" + std::to_string(d.to_step) + (d.hold_x ? "x" : "") +
          (d.hold_y ? "y" : "");
  }
  for (const Expectation& e : s.expect) {
    id += "|expect " + std::string(to_string(e.kind)) + ":" + std::to_string(e.body) + ":" +
          exact(e.center) + ":" + exact(e.moved) + ":" + exact(e.tolerance) + ":" +
          optional(e.min_x) + optional(e.min_y) + optional(e.max_x) + optional(e.max_y) + ":" +
          exact(e.speed) + ":" + exact(e.depth) + ":" +
          (e.from_step ? std::to_string(*e.from_step) : "-") + ":" +
          (e.to_step ? std::to_string(*e.to_step) : "-") + ":" + std::to_string(e.other);
    for (const std::size_t b : e.bodies) {
      id.push_back(',');
      id.append(std::to_string(b));
    }
  }
  return grid_fingerprint(id);
}

std::string grid_fingerprint(std::string_view description) {
  Fnv1a h;
  h.add(description);
  return hex(h.value);
}

nlohmann::ordered_json shard_json(const ShardOrigin& origin, const Shard& shard,
                                  const std::vector<std::size_t>& units) {
  return {{"command", origin.command},
          {"version", origin.version},
          {"grid", origin.grid},
          {"index", shard.index},
          {"count", shard.count},
          {"units", origin.units},
          {"ran", units}};
}

}  // namespace chainbench
