// SPDX-License-Identifier: MIT
#include "model/scene.h"
#include "support/number_text.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <unordered_set>

namespace chainbench {
namespace {

std::string num(double v) {
  return exact_number(v);
}

class Checker {
 public:
  void finite_within(const std::string& path, double v, double lo, double hi, const char* what) {
    if (!std::isfinite(v)) {
      add(path, "must be a finite number, got " + num(v));
    } else if (v < lo || v > hi) {
      add(path, std::string("must be ") + what + ", got " + num(v));
    }
  }
  void positive_within(const std::string& path, double v, double hi, const char* what) {
    if (!std::isfinite(v) || v <= 0.0 || v > hi) {
      add(path, std::string("must be ") + what + ", got " + num(v));
    }
  }
  void add(std::string path, std::string reason) {
    issues.push_back({std::move(path), std::move(reason)});
  }
  std::vector<SceneIssue> issues;
};

std::string life_text(const SceneBody& b) {
  return b.to_step == std::numeric_limits<int>::max()
             ? "from state " + std::to_string(b.from_step)
             : "in states " + std::to_string(b.from_step) + ".." + std::to_string(b.to_step);
}

void check_expectation(Checker& c, const Scene& s, std::size_t i) {
  namespace L = limits;
  using Kind = Expectation::Kind;
  const Expectation& e = s.expect[i];
  const std::string at = "expect[" + std::to_string(i) + "]";
  const bool every = e.body == Expectation::kEveryDynamic;
  const bool any_dynamic = std::any_of(s.bodies.begin(), s.bodies.end(), [](const SceneBody& b) {
    return b.kind == BodyKind::kDynamic;
  });
  const bool relation = is_relation(e.kind);
  if (e.kind != Kind::kNoOverlap) {
    if (every && relation) {
      c.add(at + ".body", std::string("\"*\" cannot be ") + to_string(e.kind) + ": name a body");
    } else if (every && !any_dynamic) {
      c.add(at + ".body", "\"*\" names every dynamic body, and the scene has none");
    } else if (every && e.kind == Kind::kCenter) {
      c.add(at + ".body", "\"*\" cannot have one expected centre: name a body");
    } else if (!every && e.body >= s.bodies.size()) {
      c.add(at + ".body", "names no body of the scene");
    }
  }
  if (relation && e.kind != Kind::kSqueezed) {
    const std::string key = at + "." + to_string(e.kind);
    if (e.other >= s.bodies.size()) {
      c.add(key, "names no body of the scene");
    } else if (!every && e.other == e.body) {
      c.add(key, "names the entry's own body: name another");
    }
  }
  if (relation) c.positive_within(at + ".tolerance", e.tolerance, 1e6, "> 0 and <= 1e6 m");
  if (e.kind == Kind::kNoOverlap && !e.bodies.empty()) {
    if (e.bodies.size() < 2) c.add(at + ".bodies", "must name at least two bodies");
    std::vector<std::size_t> seen;
    for (std::size_t k = 0; k < e.bodies.size(); ++k) {
      const std::string path = at + ".bodies[" + std::to_string(k) + "]";
      if (e.bodies[k] >= s.bodies.size()) {
        c.add(path, "names no body of the scene");
      } else if (std::find(seen.begin(), seen.end(), e.bodies[k]) != seen.end()) {
        c.add(path, "\"" + s.bodies[e.bodies[k]].name + "\" is named twice");
      }
      seen.push_back(e.bodies[k]);
    }
  }
  auto coordinate = [&](const std::string& path, double v) {
    c.finite_within(path, v, -L::kMaxCoordinate, L::kMaxCoordinate, "within +-1e8 m");
  };
  switch (e.kind) {
    case Kind::kCenter:
      coordinate(at + ".center[0]", e.center.x);
      coordinate(at + ".center[1]", e.center.y);
      c.positive_within(at + ".tolerance", e.tolerance, 1e6, "> 0 and <= 1e6 m");
      break;
    case Kind::kMoved:
      coordinate(at + ".moved[0]", e.moved.x);
      coordinate(at + ".moved[1]", e.moved.y);
      c.positive_within(at + ".tolerance", e.tolerance, 1e6, "> 0 and <= 1e6 m");
      break;
    case Kind::kBounds: {
      if (!e.min_x && !e.min_y && !e.max_x && !e.max_y) {
        c.add(at, "min and max bound no axis: give a number for x or y");
      }
      const char* axis[2] = {"x", "y"};
      const std::optional<double>* lo[2] = {&e.min_x, &e.min_y};
      const std::optional<double>* hi[2] = {&e.max_x, &e.max_y};
      for (int a = 0; a < 2; ++a) {
        if (*lo[a]) coordinate(at + ".min[" + std::to_string(a) + "]", **lo[a]);
        if (*hi[a]) coordinate(at + ".max[" + std::to_string(a) + "]", **hi[a]);
        if (*lo[a] && *hi[a] && **lo[a] > **hi[a]) {
          c.add(at + ".min[" + std::to_string(a) + "]", std::string(axis[a]) + " min " +
                                                            num(**lo[a]) + " is above " + axis[a] +
                                                            " max " + num(**hi[a]));
        }
      }
      break;
    }
    case Kind::kAtRest:
      c.finite_within(at + ".at_rest", e.speed, 0.0, L::kMaxSpeed, "in [0, 1e5] m/s");
      break;
    case Kind::kNoOverlap:
      c.finite_within(at + ".no_overlap", e.depth, 0.0, L::kMaxHalfExtent, "in [0, 1e6] m");
      break;
    case Kind::kAbove:
    case Kind::kBelow:
    case Kind::kOn:
    case Kind::kSqueezed:
      break;  // checked above
  }
  if (e.from_step && (*e.from_step < 0 || *e.from_step > s.steps)) {
    c.add(at + ".from_step", "must be in [0, " + std::to_string(s.steps) +
                                 "] (the scene's steps), got " + std::to_string(*e.from_step));
  }
  if (e.to_step && (*e.to_step < 0 || *e.to_step > s.steps)) {
    c.add(at + ".to_step", "must be in [0, " + std::to_string(s.steps) +
                               "] (the scene's steps), got " + std::to_string(*e.to_step));
  }
  if (e.from_step && e.to_step && *e.to_step < *e.from_step) {
    c.add(at + ".to_step", "must be >= from_step (" + std::to_string(*e.from_step) + "), got " +
                               std::to_string(*e.to_step));
  }
  // A named body is judged only in states it exists in: a window reaching outside its life
  // would judge a body that is not there. So is the body a relation names beside it.
  const int first = e.first_state(s.steps), last = e.last_state(s.steps);
  auto within_life = [&](std::size_t body, const std::string& named_by) {
    const SceneBody& b = s.bodies[body];
    if (first < b.from_step || last > b.to_step) {
      // An entry without a window is judged on the final state: it has no key to blame but itself.
      const std::string what =
          e.windowed() ? "checks states " + std::to_string(first) + ".." + std::to_string(last)
                       : "checks the final state, " + std::to_string(last);
      c.add(at + (!e.windowed()         ? ""
                  : first < b.from_step ? ".from_step"
                                        : ".to_step"),
            what + ", outside the life of body \"" + b.name + "\" (" + named_by + "it exists " +
                life_text(b) + ")");
    }
  };
  if (e.kind != Kind::kNoOverlap && !every && e.body < s.bodies.size()) within_life(e.body, "");
  if (relation && e.kind != Kind::kSqueezed && e.other < s.bodies.size() && e.other != e.body)
    within_life(e.other, std::string("named by \"") + to_string(e.kind) + "\"; ");
}

}  // namespace

std::vector<SceneIssue> validate(const Scene& s) {
  namespace L = limits;
  Checker c;
  if (s.steps < 1 || s.steps > L::kMaxSteps)
    c.add("steps", "must be in [1, 10000000], got " + std::to_string(s.steps));
  if (!std::isfinite(s.dt) || s.dt < L::kMinDt || s.dt > L::kMaxDt)
    c.add("dt", "must be in [" + num(L::kMinDt) + ", " + num(L::kMaxDt) + "] s, got " + num(s.dt));
  c.finite_within("gravity[0]", s.gravity.x, -L::kMaxGravity, L::kMaxGravity, "within +-1e4 m/s^2");
  c.finite_within("gravity[1]", s.gravity.y, -L::kMaxGravity, L::kMaxGravity, "within +-1e4 m/s^2");
  c.finite_within("friction", s.friction, 0.0, L::kMaxFriction, "in [0, 10]");
  c.finite_within("restitution", s.restitution, 0.0, 1.0, "in [0, 1]");
  if (s.bodies.empty()) c.add("bodies", "must hold at least one body");
  if (s.bodies.size() > L::kMaxBodies)
    c.add("bodies",
          "holds " + std::to_string(s.bodies.size()) + " bodies, more than the limit of 4000000");
  if (s.drivers.size() > L::kMaxDrivers) c.add("drivers", "holds more than 1000000 drivers");
  if (s.expect.size() > L::kMaxExpectations) c.add("expect", "holds more than 1000000 entries");

  std::unordered_set<std::string> names;
  for (std::size_t i = 0; i < s.bodies.size() && i < L::kMaxBodies; ++i) {
    const SceneBody& b = s.bodies[i];
    const std::string at = "bodies[" + std::to_string(i) + "]";
    if (!b.name.empty() && !names.insert(b.name).second)
      c.add(at + ".name", "\"" + b.name + "\" names two bodies");
    if (b.name == "*") c.add(at + ".name", "\"*\" is kept for \"every dynamic body\" in expect");
    c.finite_within(at + ".center[0]", b.center.x, -L::kMaxCoordinate, L::kMaxCoordinate,
                    "within +-1e8 m");
    c.finite_within(at + ".center[1]", b.center.y, -L::kMaxCoordinate, L::kMaxCoordinate,
                    "within +-1e8 m");
    c.positive_within(at + ".half_extents[0]", b.half_extents.x, L::kMaxHalfExtent,
                      "> 0 and <= 1e6 m");
    c.positive_within(at + ".half_extents[1]", b.half_extents.y, L::kMaxHalfExtent,
                      "> 0 and <= 1e6 m");
    c.finite_within(at + ".velocity[0]", b.velocity.x, -L::kMaxSpeed, L::kMaxSpeed,
                    "within +-1e5 m/s");
    c.finite_within(at + ".velocity[1]", b.velocity.y, -L::kMaxSpeed, L::kMaxSpeed,
                    "within +-1e5 m/s");
    if (b.kind == BodyKind::kStatic && (b.velocity.x != 0.0 || b.velocity.y != 0.0)) {
      c.add(at + ".velocity", "must be zero for a static body (make it kinematic to move it)");
    }
    if (b.kind == BodyKind::kDynamic) {
      c.positive_within(at + ".mass", b.mass, L::kMaxMass, "> 0 and <= 1e15 kg for a dynamic body");
      c.finite_within(at + ".gravity_scale", b.gravity_scale, -100.0, 100.0, "within +-100");
    }
    if (b.friction)
      c.finite_within(at + ".friction", *b.friction, 0.0, L::kMaxFriction, "in [0, 10]");
    if (b.restitution) c.finite_within(at + ".restitution", *b.restitution, 0.0, 1.0, "in [0, 1]");
    if (b.penetration_tolerance)
      c.positive_within(at + ".penetration_tolerance", *b.penetration_tolerance, L::kMaxHalfExtent,
                        "> 0 and <= 1e6 m");
    if (b.from_step < 0 || b.from_step > L::kMaxSteps)
      c.add(at + ".from_step", "must be in [0, 10000000], got " + std::to_string(b.from_step));
    if (b.to_step <= b.from_step)
      c.add(at + ".to_step", "must be > from_step (" + std::to_string(b.from_step) +
                                 "): the body takes part in steps from_step..to_step - 1, got " +
                                 std::to_string(b.to_step));
  }
  for (std::size_t i = 0; i < s.drivers.size() && i < L::kMaxDrivers; ++i) {
    const Driver& d = s.drivers[i];
    const std::string at = "drivers[" + std::to_string(i) + "]";
    if (d.body >= s.bodies.size()) {
      c.add(at + ".body", "names no body of the scene");
    } else if (s.bodies[d.body].kind == BodyKind::kStatic) {
      c.add(at + ".body", "names a static body, which cannot be driven");
    }
    c.finite_within(at + ".velocity[0]", d.velocity.x, -L::kMaxSpeed, L::kMaxSpeed,
                    "within +-1e5 m/s");
    c.finite_within(at + ".velocity[1]", d.velocity.y, -L::kMaxSpeed, L::kMaxSpeed,
                    "within +-1e5 m/s");
    if (d.from_step < 0)
      c.add(at + ".from_step", "must be >= 0, got " + std::to_string(d.from_step));
    if (d.to_step < d.from_step)
      c.add(at + ".to_step", "must be >= from_step, got " + std::to_string(d.to_step));
    // A drive outside its body's life would set the velocity of a body that is not there.
    if (d.body < s.bodies.size() && d.to_step > d.from_step) {
      const SceneBody& b = s.bodies[d.body];
      const int last = std::min(d.to_step, s.steps);
      if (d.from_step < b.from_step || (last > b.to_step && d.from_step < s.steps)) {
        c.add(at + (d.from_step < b.from_step ? ".from_step" : ".to_step"),
              "drives steps " + std::to_string(d.from_step) + ".." + std::to_string(last - 1) +
                  ", outside the life of body \"" + b.name + "\" (it exists " + life_text(b) + ")");
      }
    }
  }
  for (std::size_t i = 0; i < s.expect.size() && i < L::kMaxExpectations; ++i)
    check_expectation(c, s, i);
  if (s.penetration_tolerance) {
    c.positive_within("penetration_tolerance", *s.penetration_tolerance, L::kMaxHalfExtent,
                      "> 0 and <= 1e6 m");
  }
  return c.issues;
}

bool Scene::filters() const {
  return std::any_of(bodies.begin(), bodies.end(), [](const SceneBody& b) {
    return b.category_bits != 0x0001 || b.mask_bits != 0xFFFF;
  });
}

bool Scene::has_belts() const {
  return std::any_of(bodies.begin(), bodies.end(), [](const SceneBody& b) {
    return b.surface_velocity.x != 0.0 || b.surface_velocity.y != 0.0;
  });
}

bool Scene::has_lifetimes() const {
  return std::any_of(bodies.begin(), bodies.end(),
                     [](const SceneBody& b) { return b.comes_or_goes(); });
}

Extent initial_extent(const Scene& s) {
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool first = true;
  for (const SceneBody& b : s.bodies) {
    const double bx0 = b.center.x - b.half_extents.x, bx1 = b.center.x + b.half_extents.x;
    const double by0 = b.center.y - b.half_extents.y, by1 = b.center.y + b.half_extents.y;
    x0 = first ? bx0 : std::min(x0, bx0), x1 = first ? bx1 : std::max(x1, bx1);
    y0 = first ? by0 : std::min(y0, by0), y1 = first ? by1 : std::max(y1, by1);
    first = false;
  }
  return {{0.5 * (x0 + x1), 0.5 * (y0 + y1)}, 0.5 * std::hypot(x1 - x0, y1 - y0)};
}

const char* to_string(Expectation::Kind kind) {
  switch (kind) {
    case Expectation::Kind::kCenter:
      return "center";
    case Expectation::Kind::kMoved:
      return "moved";
    case Expectation::Kind::kBounds:
      return "bounds";
    case Expectation::Kind::kAtRest:
      return "at_rest";
    case Expectation::Kind::kNoOverlap:
      return "no_overlap";
    case Expectation::Kind::kAbove:
      return "above";
    case Expectation::Kind::kBelow:
      return "below";
    case Expectation::Kind::kOn:
      return "on";
    case Expectation::Kind::kSqueezed:
      return "squeezed";
  }
  return "?";
}

bool is_relation(Expectation::Kind kind) {
  using Kind = Expectation::Kind;
  return kind == Kind::kAbove || kind == Kind::kBelow || kind == Kind::kOn ||
         kind == Kind::kSqueezed;
}

double Scene::pair_penetration_tolerance(std::size_t i, std::size_t j) const {
  const std::optional<double>& a = bodies[i].penetration_tolerance;
  const std::optional<double>& b = bodies[j].penetration_tolerance;
  if (a && b) return std::min(*a, *b);
  if (a || b) return a ? *a : *b;
  if (penetration_tolerance) return *penetration_tolerance;
  const Vec2d hi = bodies[i].half_extents, hj = bodies[j].half_extents;
  return 0.1 * std::min({hi.x, hi.y, hj.x, hj.y});
}

const char* to_string(BodyKind kind) {
  switch (kind) {
    case BodyKind::kStatic:
      return "static";
    case BodyKind::kKinematic:
      return "kinematic";
    case BodyKind::kDynamic:
      return "dynamic";
  }
  return "?";
}

}  // namespace chainbench
