// SPDX-License-Identifier: MIT
// The scene model: one description of boxes, drives and expectations that every engine is built
// from. Plain data in metres, kilograms and seconds, y up; body order is body identity.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace chainbench {

struct Vec2d {
  double x = 0.0;
  double y = 0.0;
  friend bool operator==(const Vec2d&, const Vec2d&) = default;
};

enum class BodyKind { kStatic, kKinematic, kDynamic };

struct SceneBody {
  std::string name;
  BodyKind kind = BodyKind::kDynamic;
  Vec2d center;
  Vec2d half_extents{0.5, 0.5};
  Vec2d velocity;     // initial; a kinematic body keeps it
  double mass = 1.0;  // dynamic bodies only
  double gravity_scale = 1.0;
  std::optional<double> friction;     // else the scene's
  std::optional<double> restitution;  // else the scene's
  // What another box may overlap this one, m, before the run is `penetrating`; see
  // pair_penetration_tolerance(). (Initialised so that brace lists of the fields above stay whole.)
  std::optional<double> penetration_tolerance = std::nullopt;
  // Collision filtering (Box2D's rule): two bodies collide when each one's category is in the
  // other's mask; pairs that do not collide pass through each other and are never judged.
  std::uint16_t category_bits = 0x0001;
  std::uint16_t mask_bits = 0xFFFF;
  // A conveyor's belt (static and kinematic bodies): friction acts on what touches it as if its
  // surface moved at this on top of the body's own velocity, m/s; the scene file allows [vx, 0].
  Vec2d surface_velocity = Vec2d{};
  // Its life: it takes part in steps n with from_step <= n < to_step, so it exists in states
  // from_step..to_step. It enters as center and velocity say, and leaves after step to_step - 1.
  int from_step = 0;
  int to_step = std::numeric_limits<int>::max();

  // Whether the body exists in state k (k steps taken).
  bool alive(int k) const { return from_step <= k && k <= to_step; }
  bool comes_or_goes() const { return from_step > 0 || to_step != std::numeric_limits<int>::max(); }
};

// Holds the body's velocity along the axes it names at the start of every step n with
// from_step <= n < to_step, as a character controller would; an axis it leaves free is left to
// gravity and contacts (a walking character holds x and falls along y).
struct Driver {
  std::size_t body = 0;
  Vec2d velocity;
  int from_step = 0;
  int to_step = std::numeric_limits<int>::max();
  bool hold_x = true;
  bool hold_y = true;
};

// What a scene says is physically right, checked for every engine by the harness. One entry
// states one fact:
//   kCenter     the body's centre within `tolerance` metres of `center`
//   kMoved      the body's centre within `tolerance` metres of where it started plus `moved`
//               ((0, 0): it stays put)
//   kBounds     the body's centre within [min, max] on each axis that has a bound
//   kAtRest     the body's speed, measured from its displacement in a step, at most `speed` m/s
//   kNoOverlap  no two boxes (at least one dynamic) overlap deeper than `depth` metres; with
//               `bodies`, no two of the bodies named there (of any kind)
//   kAbove      the body's bottom face at or above `other`'s top face less `tolerance` metres
//   kBelow      the body's top face at or below `other`'s bottom face plus `tolerance` metres
//   kOn         the body's bottom face within `tolerance` metres of `other`'s top face, and the
//               two overlapping along x
//   kSqueezed   the body within `tolerance` metres of (or overlapping) static or kinematic bodies
//               on two opposite sides (left and right, or below and above)
// Faces are those of each box's axis-aligned extent at its angle. kMoved, kBounds and kAtRest may
// name every dynamic body at once (kEveryDynamic). Without a window
// an entry is checked on the final state; with one, on every state k (k steps taken, 0 = as built)
// with from_step <= k <= to_step.
struct Expectation {
  enum class Kind { kCenter, kMoved, kBounds, kAtRest, kNoOverlap, kAbove, kBelow, kOn, kSqueezed };
  static constexpr std::size_t kEveryDynamic = std::numeric_limits<std::size_t>::max();

  Kind kind = Kind::kCenter;
  std::size_t body = 0;  // a body index or kEveryDynamic; unused by kNoOverlap
  Vec2d center;
  Vec2d moved;
  double tolerance = 0.01;
  std::optional<double> min_x, min_y, max_x, max_y;
  double speed = 0.0;
  double depth = 0.0;
  std::optional<int> from_step, to_step;
  std::size_t other = 0;            // kAbove, kBelow, kOn: the body the fact relates `body` to
  std::vector<std::size_t> bodies;  // kNoOverlap: the bodies whose pairs count; empty: all

  bool windowed() const { return from_step.has_value() || to_step.has_value(); }
  // The states the entry is checked on in a run of `steps` steps: [first, last].
  int first_state(int steps) const { return windowed() ? from_step.value_or(0) : steps; }
  int last_state(int steps) const { return to_step.value_or(steps); }
};

const char* to_string(Expectation::Kind kind);
// Whether the kind relates a body to others (kAbove, kBelow, kOn, kSqueezed): judged from the
// positions of several bodies, its error in metres.
bool is_relation(Expectation::Kind kind);

struct Scene {
  std::string name;
  std::string description;
  std::string
      family;  // a built-in scene's (stacking, pushing, level, moving, ...); empty for a file
  Vec2d gravity{0.0, -10.0};
  double dt = 1.0 / 60.0;
  int steps = 120;
  bool rotation = false;
  double friction = 0.0;
  double restitution = 0.0;
  std::vector<SceneBody> bodies;
  std::vector<Driver> drivers;
  std::vector<Expectation> expect;
  // Overlaps deeper than this (metres) make a run `penetrating`; unset: 5% of the smaller box of
  // each overlapping pair. A case that must squeeze boxes sets what the squeeze forces.
  std::optional<double> penetration_tolerance;

  double friction_of(const SceneBody& b) const { return b.friction.value_or(friction); }
  double restitution_of(const SceneBody& b) const { return b.restitution.value_or(restitution); }
  // What bodies i and j may overlap, m, before the run is `penetrating`: the smaller of the two
  // bodies' own tolerances where either has one (each body's is a promise about that body, so a
  // pair keeps both), else the scene's, else 0.1 x the smallest of the two boxes' half extents.
  double pair_penetration_tolerance(std::size_t i, std::size_t j) const;
  // Whether bodies i and j collide (SceneBody::category_bits, mask_bits).
  bool collide(std::size_t i, std::size_t j) const {
    const SceneBody &a = bodies[i], &b = bodies[j];
    return (a.category_bits & b.mask_bits) != 0 && (b.category_bits & a.mask_bits) != 0;
  }
  // Whether some body filters (has category or mask bits other than 1 and 0xFFFF).
  bool filters() const;
  // Whether some body is a conveyor (has a surface_velocity).
  bool has_belts() const;
  bool has_gravity() const { return gravity.x != 0.0 || gravity.y != 0.0; }
  // Whether some body enters after the start or leaves before the end (SceneBody::from_step).
  bool has_lifetimes() const;
};

// Limits every scene must respect, however it was made: they keep the engines in the range where
// their arithmetic means something and a run in the range a machine can hold.
namespace limits {
inline constexpr int kMaxSteps = 10'000'000;
inline constexpr std::size_t kMaxBodies = 4'000'000;
inline constexpr std::size_t kMaxDrivers = 1'000'000;
inline constexpr std::size_t kMaxExpectations = 1'000'000;
inline constexpr double kMinDt = 1e-6;
inline constexpr double kMaxDt = 1.0;
inline constexpr double kMaxCoordinate = 1e8;
inline constexpr double kMaxHalfExtent = 1e6;
inline constexpr double kMaxSpeed = 1e5;
inline constexpr double kMaxMass = 1e15;
inline constexpr double kMaxGravity = 1e4;
inline constexpr double kMaxFriction = 10.0;
}  // namespace limits

// A problem found in a scene: where (a JSON path such as "bodies[3].half_extents") and why.
struct SceneIssue {
  std::string path;
  std::string reason;
};

// Every violation of the rules above and of the body rules (sizes > 0, dynamic mass > 0, unique
// names, drivers and expectations naming bodies that exist...). Empty when the scene is valid.
std::vector<SceneIssue> validate(const Scene& scene);

// The centre of the scene's bounding box and the largest distance from it to a box corner.
struct Extent {
  Vec2d center;
  double radius = 0.0;
};
Extent initial_extent(const Scene& scene);

const char* to_string(BodyKind kind);

}  // namespace chainbench
