// SPDX-License-Identifier: MIT
// A world of axis-aligned boxes resolved by collision chaining.
//
// Units: metres, kilograms, seconds; y points up. Each step of dt seconds:
//   1. Drives set the velocity components they hold, gravity accelerates dynamic bodies, and every
//      movable body moves by velocity * dt.
//   2. Continuous collision (modern): a body that moved far for its size this step is swept along
//      its path (see "Fast bodies" below).
//   3. Overlapping boxes are pushed apart by chaining: a push that causes a new overlap is resolved
//      in turn, with the pushing mass accumulated down the chain. A dynamic body is pushed out of
//      a static or kinematic body through the face it came in through (modern): from where it
//      was at the start of the step relative to that body, so the joins between flush tiles are
//      neither snagged on nor pushed sideways from, and a body never comes out on the far side.
//   4. Velocities: the velocity rule, then friction (modern); touching flags and crush events.
//      A body squeezed between two static or kinematic bodies along an axis is centred between
//      them; a row of bodies squeezed so (modern) shares the squeeze evenly, every contact along it
//      overlapping by the same depth, and every body of it is reported crushed, once a step.
// A world at rest skips its steps (modern, WorldDef::skip_rest): once two steps in a row left
// every movable body where it began them at velocity +0, each step after them is the fixed point
// it would rebuild, until the API changes a body or dt changes (StepStats::skipped). So does a
// part of a world: an island of bodies at rest that nothing else came within a touch of is left
// out of the steps after it, until a body that may reach it, or the API, wakes it
// (StepStats::resting); a step that finds it guessed wrong is solved again whole
// (StepStats::redone). The bits are those of solving every body, every step.
//
// Fast bodies (modern). A dynamic body is fast in a step when it moves more than half its half
// extent along an axis; a kinematic body, more than its half extent.
//   - Against static and kinematic bodies: no dynamic body passes through one, at any speed up to
//     kMaxSpeed and any dt. A fast body's motion is swept; at each static or kinematic face it
//     meets it stops moving into that face and slides on along it (up to 4 faces a step; after
//     the 4th it stops for the rest of the step), as a slow body resting there would. What a fast
//     kinematic body carries keeps its order along the motion: a stack on it stays a stack. The one
//     exception is a squeeze, fast or slow: a body pressed between two immovable bodies (a
//     platform lifting it into a ceiling) is reported as a crush event, and a kinematic body that
//     keeps going then passes it.
//   - Against dynamic bodies: a fast dynamic body is swept against the straight-line motion of
//     every other dynamic body over the step. Where it would end too deep in one for push-out to
//     send it back the way it came (past 90% of the way to the other's centre along the axis it
//     met on, or deeper along that axis than 90% of the overlap across it, or past the body), it
//     is moved back along its path to that depth; anywhere shallower it keeps its whole move.
//     Push-out then resolves the collision as between slow bodies (mass split, chains, velocity
//     rule): a driven pusher pushes as far at any speed as push-out alone would. So a fast body
//     never passes through a body that moves as integrated, at any speed. Not guaranteed: if both
//     bodies are fast and one is stopped earlier in the step by a third body, the other may miss
//     it.
//   - Pushes (modern): a push moves a body at once by up to an overlap depth. A push longer than
//     a tenth of the pushed body's own half extent along it stops where the body would be 90% of
//     the way to the centre of a body it meets (across at least half the smaller box), so push-out
//     never lands a body on or past another's centre, where it would send it on through; what is
//     left of the overlap is resolved by the chain or the next pass. Boxes created overlapping
//     are so pushed apart without one crossing another in a push.
//
// The solver depends on the C++ standard library only; this header compiles as C++17 or later.
// Any function that allocates may also throw std::bad_alloc.
#pragma once

#include <chain/types.h>

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

namespace chain {

namespace detail {
struct WorldAccess;  // the library's and its tests' way in (solver/src/world_access.h)
}  // namespace detail

// Inputs beyond these limits are rejected: far outside them double arithmetic stops being
// meaningful, and near double's own limit it overflows.
inline constexpr double kMaxCoordinate = 1.0e9;  // |center| components, metres
inline constexpr double kMaxHalfExtent = 1.0e8;  // metres
inline constexpr double kMaxSpeed = 1.0e6;       // |velocity| components, m/s
inline constexpr double kMaxMass = 1.0e18;       // kg
inline constexpr double kMaxGravity = 1.0e6;     // |gravity| components, m/s^2
inline constexpr double kMaxFriction = 1.0e6;    // friction coefficient, dimensionless
inline constexpr int kMaxThreads = 256;          // WorldDef::threads

// A body to add. World::create_body refuses (std::invalid_argument) a definition for which
// validate() is not empty; the limits are given per field.
struct BodyDef {
  BodyType type = BodyType::kDynamic;
  Vec2 center;                  // m; components finite, |c| <= kMaxCoordinate
  Vec2 half_extents{0.5, 0.5};  // m; each > 0 and <= kMaxHalfExtent
  // m/s, initial; components finite, |v| <= kMaxSpeed; must be zero for a static body. A
  // kinematic body keeps it until set_velocity or a drive changes it.
  Vec2 velocity;
  double mass = 1.0;           // kg; dynamic bodies only: > 0 and <= kMaxMass (else ignored)
  double gravity_scale = 1.0;  // dynamic bodies only: finite, |s| <= 1e6 (else ignored)
  double restitution = 0.0;    // in [0, 1]; the inelastic rule bounces by it (modern, seed2014)
  // Coulomb friction coefficient, in [0, kMaxFriction], any body type. A contact's coefficient is
  // sqrt(fa * fb), the geometric mean rigid-body engines commonly use, so a body with 0 never rubs.
  // Modern variant only, both velocity rules (seed2014 ignores it); with 0 on every body nothing
  // changes, to the bit. Push-out leaves no forces, so the normal impulse friction is bounded by is
  // the momentum the step's push-out and velocity rule took out of the bodies a contact holds up,
  // handed down through their supports (split evenly where a body rests on several): the bottom
  // contact of a resting stack carries the whole stack's weight, M g dt a step, and a stack on a
  // moving platform is carried as one. Friction never changes a component a drive holds, and moves
  // a body by half the velocity it took, times dt, so a box sliding at v stops after v^2/(2 mu g).
  double friction = 0.0;
  // Collision filtering, as Box2D's: two bodies collide when each one's category is in the other's
  // mask ((a.category_bits & b.mask_bits) != 0 and (b.category_bits & a.mask_bits) != 0). Bodies
  // that do not collide pass through each other: they are never pushed apart, swept against,
  // carried by one another, nor count as joining a surface (seams). Both variants.
  std::uint16_t category_bits = 0x0001;
  std::uint16_t mask_bits = 0xFFFF;
  // A conveyor: static and kinematic bodies only (else zero), m/s, components within kMaxSpeed.
  // Friction acts on what touches the body as if its surface moved at this velocity on top of the
  // body's own (a belt): a crate resting on a static belt of surface velocity (v, 0) slips until
  // it moves at v, as on a platform moving at v. Push-out is unchanged. Modern variant only.
  Vec2 surface_velocity;
};

// A world's settings. World's constructor refuses (std::invalid_argument) a definition for which
// validate() is not empty; the limits are given per field.
struct WorldDef {
  Variant variant = Variant::kModern;
  VelocityRule velocity_rule = VelocityRule::kInelastic;
  Vec2 gravity{0.0, -10.0};  // m/s^2; components finite, |g| <= kMaxGravity
  // Modern: contact passes per step, in [1, 1000]; a pass runs only while the previous one left
  // overlaps.
  int max_passes = 4;
  // Both variants: pair resolutions allowed per step, per body (plus a fixed 1024), in
  // [1, 1000000]. When a step runs out, the chains still open are cut, counted in
  // StepStats::budget_hits. In the modern variant a gathering of the bodies overlapping one that
  // finds 32 or more costs one more for every 32 (boxes piled into each other, as created all in
  // one place): such a pile comes apart over more steps, each of bounded work.
  int budget_per_body = 64;
  // seed2014 resolves recursively, as the 2014 engine did: deeper chains are cut and counted. In
  // [1, 16384] (each level is a native stack frame).
  int seed_max_depth = 2048;
  // Overlaps no deeper than this are contact, not penetration (metres), in [0, 1]. A row of n
  // boxes can hold up to n times this, so it is kept near double rounding at kilometre scale.
  // Faces of immovable bodies closer than this count as flush (one surface).
  double touch_tolerance = 1.0e-9;
  // Inelastic rule: closing speeds below this do not bounce (m/s), in [0, 1e6].
  double restitution_threshold = 1.0;
  // Threads a step runs on, the caller's included, in [1, kMaxThreads]. The parts of a step that
  // split into independent blocks of bodies (contact gathering, integration, the two axes of the
  // velocity rule) are spread over them; every count gives the same bits. The workers start with
  // the world (and with each copy of it); a step allocates nothing for them.
  int threads = 1;
  // Modern: a step that would rebuild the bits it starts from is skipped (StepStats::skipped), in
  // O(1), and so are the resting islands a step would rebuild (StepStats::resting); false solves
  // every body every step. Either gives the same bits, body for body, every step.
  bool skip_rest = true;
};

// Empty when `def` can be added to a world; otherwise the reason, naming the field. No throw
// but std::bad_alloc.
std::string validate(const BodyDef& def);
// Empty when a world can be built from `def`; otherwise the reason, naming the field. No throw
// but std::bad_alloc.
std::string validate(const WorldDef& def);

// Every function taking a BodyId throws std::invalid_argument when no body with that id is in the
// world (never created here, or destroyed).
class World {
 public:
  // Throws std::invalid_argument (with validate()'s reason) when validate(def) is not empty.
  explicit World(const WorldDef& def = WorldDef{});
  ~World();
  World(const World& other);
  World& operator=(const World& other);
  World(World&& other) noexcept;
  World& operator=(World&& other) noexcept;

  // Adds a body and returns its id. Throws std::invalid_argument (with validate()'s reason) for a
  // bad definition, std::length_error once 2^32 - 1 bodies were created.
  BodyId create_body(const BodyDef& def);
  // Removes a body; its id is never handed out again. Throws std::invalid_argument (unknown id).
  // Cost (modern, once the world has stepped): destroying a dynamic body empties its slot, and
  // dynamic bodies created before the next step take empty slots, about what the body itself
  // costs; anything else (a static or kinematic body, more bodies created than slots emptied, a
  // body larger than any in the world) re-sorts the whole world at the next step.
  void destroy_body(BodyId id);
  bool contains(BodyId id) const noexcept;
  std::size_t body_count() const noexcept;

  // A drive sets the velocity components it holds (m/s) at the start of every step until cleared,
  // as a character controller would; gravity still acts within the step, and contacts may change
  // the velocity after it. An axis it does not hold is left free: set_drive(id, {4, 0},
  // DriveAxes::kX) walks at 4 m/s and falls off a ledge. Friction never changes a held component.
  // Both variants (seed2014 applies it the same way, in its integration). Dynamic and kinematic
  // bodies only. Throws std::invalid_argument for an unknown id, a static body, a held component
  // that is not finite or beyond kMaxSpeed, or `axes` not a DriveAxes value. Replaces any drive
  // the body had; the two-argument form holds both axes.
  void set_drive(BodyId id, Vec2 velocity, DriveAxes axes);
  void set_drive(BodyId id, Vec2 velocity) { set_drive(id, velocity, DriveAxes::kBoth); }
  // Ends the body's drive, if any; it keeps the velocity it has. Throws std::invalid_argument
  // (unknown id).
  void clear_drive(BodyId id);
  // Sets the body's velocity now (m/s). Throws std::invalid_argument for an unknown id, a static
  // body, or a component that is not finite or beyond kMaxSpeed.
  void set_velocity(BodyId id, Vec2 velocity);

  // Centre (m) and velocity (m/s) after the last step. Throw std::invalid_argument (unknown id).
  Vec2 position(BodyId id) const;
  Vec2 velocity(BodyId id) const;
  // touching:: bits for the sides on which the body was pushed during the last step. Throws
  // std::invalid_argument (unknown id).
  std::uint8_t touching_flags(BodyId id) const;
  // Positions (m) and velocities (m/s) of `ids`, in that order; either output may be empty to
  // skip it. Throws std::invalid_argument for a non-empty output shorter than ids (before
  // writing anything) or an unknown id (after writing the entries before it).
  void read_state(Span<const BodyId> ids, Span<Vec2> positions, Span<Vec2> velocities) const;
  // Every body's id, centre (m) and velocity (m/s), entry k of each output for the same body, in
  // the order the world stores them (it changes when the world renumbers its bodies): one pass
  // through memory, where read_state() looks each id up. Any output may be empty to skip it.
  // Throws std::invalid_argument for a non-empty output shorter than body_count(), before
  // writing anything.
  void read_all(Span<BodyId> ids, Span<Vec2> positions, Span<Vec2> velocities) const;
  // Brings a full copy that read_all() made up to date with the world now, in one pass through
  // memory: every entry k whose id, centre or velocity differs (in bits, and a NaN always does)
  // is overwritten, and k appended to `changed` (cleared first), in ascending order. Throws
  // std::invalid_argument for an output shorter than body_count(), before writing anything.
  void update_all(Span<BodyId> ids, Span<Vec2> positions, Span<Vec2> velocities,
                  std::vector<std::uint32_t>& changed) const;

  // Advances by dt seconds. Throws std::invalid_argument unless dt is finite and > 0; any dt is
  // valid, and fast bodies are swept whatever it is (modern). A step whose gravity would sink a
  // dynamic box past its half extent is taken as up to 64 equal sub-steps that each sink it less
  // (modern; StepStats::substeps), drives setting their velocities at the first only, so resting
  // stacks hold at any dt; the step reports all of them together. Throws std::length_error for a
  // modern world of 2^30 bodies or more (its near lists keep 32-bit box offsets).
  // Deterministic: the same bodies, in any creation order, give the same bits (modern variant);
  // so do the bodies created and destroyed between two steps, in any order of the calls.
  // Bodies that reach one state are told apart by what each was created as (its BodyDef), so
  // only two bodies created identical (same BodyDef, same drive) and still so may trade places.
  // Allocates nothing once the world's buffers have grown to their working size.
  void step(double dt);

  const StepStats& last_step_stats() const noexcept;
  // Measures each stage of the steps that follow (StepProfile), or stops. Off by default: it
  // reads the clock about a dozen times a step (well under a microsecond), which a world of a few
  // bodies would feel. Changes no result.
  void set_profiling(bool on) noexcept;
  // The last step's stage times; all zero unless profiling was on for it.
  const StepProfile& last_step_profile() const noexcept;
  // Crush events of the last step, in a deterministic order; valid until the next step.
  Span<const CrushEvent> crush_events() const noexcept;
  const WorldDef& def() const noexcept;

 private:
  friend struct detail::WorldAccess;
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace chain
