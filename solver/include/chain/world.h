// A world of axis-aligned boxes resolved by collision chaining.
//
// Each step applies drives and gravity to velocities, integrates positions, pushes overlapping
// boxes apart by chaining (a push that causes a new overlap is resolved in turn, with the pushing
// mass accumulated down the chain), then updates velocities, touching flags and crush events.
// The solver depends on the C++ standard library only.
#pragma once

#include <chain/types.h>

#include <cstddef>
#include <memory>
#include <span>
#include <string>

namespace chain {

// Inputs beyond these limits are rejected: far outside them double arithmetic stops being
// meaningful, and near double's own limit it overflows.
inline constexpr double kMaxCoordinate = 1.0e9;  // |center| components, metres
inline constexpr double kMaxHalfExtent = 1.0e8;  // metres
inline constexpr double kMaxSpeed = 1.0e6;       // |velocity| components, m/s
inline constexpr double kMaxMass = 1.0e18;       // kg
inline constexpr double kMaxGravity = 1.0e6;     // |gravity| components, m/s^2

struct BodyDef {
  BodyType type = BodyType::kDynamic;
  Vec2 center;
  Vec2 half_extents{0.5, 0.5};
  Vec2 velocity;               // initial; a kinematic body keeps it
  double mass = 1.0;           // dynamic bodies only; must be > 0
  double gravity_scale = 1.0;  // dynamic bodies only
  double restitution = 0.0;    // in [0, 1]; used by the inelastic velocity rule
};

struct WorldDef {
  Variant variant = Variant::kModern;
  VelocityRule velocity_rule = VelocityRule::kInelastic;
  Vec2 gravity{0.0, -10.0};
  // Modern: contact sweeps per step; a sweep runs only while the previous one left overlaps.
  int max_passes = 4;
  // Both variants: pair resolutions allowed per step, per body (plus a fixed 1024). When a step
  // runs out, the chains still open are cut, counted in StepStats::budget_hits.
  int budget_per_body = 64;
  // seed2014 resolves recursively, as the 2014 engine did: deeper chains are cut and counted.
  int seed_max_depth = 2048;
  // Overlaps no deeper than this are contact, not penetration (metres). A row of n boxes can
  // hold up to n times this, so it is kept near double rounding at kilometre scale.
  double touch_tolerance = 1.0e-9;
  // Inelastic rule: closing speeds below this do not bounce (m/s).
  double restitution_threshold = 1.0;
};

// Empty when `def` can be added to a world; otherwise the reason, naming the field.
std::string validate(const BodyDef& def);
// Empty when a world can be built from `def`; otherwise the reason, naming the field.
std::string validate(const WorldDef& def);

class World {
 public:
  // Throws std::invalid_argument when validate(def) is not empty.
  explicit World(const WorldDef& def = WorldDef{});
  ~World();
  World(const World& other);
  World& operator=(const World& other);
  World(World&& other) noexcept;
  World& operator=(World&& other) noexcept;

  // Adds a body; throws std::invalid_argument (with validate()'s reason) for a bad definition.
  BodyId create_body(const BodyDef& def);
  // Removes a body; its id is never handed out again.
  void destroy_body(BodyId id);
  bool contains(BodyId id) const;
  std::size_t body_count() const;

  // A drive sets the body's velocity at the start of every step until cleared, as a character
  // controller would; gravity still acts within the step. Dynamic and kinematic bodies only.
  void set_drive(BodyId id, Vec2 velocity);
  void clear_drive(BodyId id);
  void set_velocity(BodyId id, Vec2 velocity);

  Vec2 position(BodyId id) const;
  Vec2 velocity(BodyId id) const;
  // touching:: bits for the sides on which the body was pushed during the last step.
  std::uint8_t touching_flags(BodyId id) const;
  // Positions and velocities of `ids`, in that order; either output may be empty to skip it.
  void read_state(std::span<const BodyId> ids, std::span<Vec2> positions,
                  std::span<Vec2> velocities) const;

  // Advances by dt seconds (finite, > 0; throws std::invalid_argument otherwise).
  // Deterministic: the same bodies, in any creation order, give the same bits (modern variant;
  // two identical bodies in the same place may trade places, as nothing tells them apart).
  void step(double dt);

  const StepStats& last_step_stats() const;
  // Crush events of the last step, in a deterministic order.
  std::span<const CrushEvent> crush_events() const;
  const WorldDef& def() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace chain
