// SPDX-License-Identifier: MIT
// Plain data shared by the solver's API: vectors, body kinds, handles, views, per-step reports.
// Units: metres, kilograms, seconds; y points up. Compiles as C++17 or later.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <utility>

#if __cplusplus >= 202002L
#include <span>
#endif

namespace chain {

// Double precision throughout: a chain of n pushes accumulates n roundings, and a float at
// 1 km already resolves only 6e-5 m.
struct Vec2 {
  double x = 0.0;  // metres (or m/s, m/s^2, by context)
  double y = 0.0;
};

enum class BodyType : std::uint8_t {
  kStatic,     // never moves
  kKinematic,  // moves at its velocity, infinite mass, never pushed
  kDynamic,    // pushed out of overlaps, moved by gravity and drives
};

// The push-out algorithm a world runs.
enum class Variant : std::uint8_t {
  kModern,    // collision chaining done right: order-independent, bounded, crush-aware, with
              // continuous collision, seam-free immovable contacts and friction
  kSeed2014,  // the 2014 engine's algorithm, quirks included (docs/algorithm-2014.md §4)
};

// What a push does to the velocities of the bodies it separates. Friction (modern, BodyDef::
// friction) acts after either rule, bounded by the normal momentum the rule took (world.h).
enum class VelocityRule : std::uint8_t {
  // A velocity component pointing into the push is set to zero (the 2014 rule); a pushed body
  // gains no velocity. Friction then slows or carries along the surface with the momentum that
  // stop took: a body resting on a moving platform is carried, a sliding one stops.
  kZero,
  // Bodies pushed against each other share a mass-weighted normal velocity (perfectly inelastic),
  // or bounce by restitution; friction acts with the momentum that change took.
  kInelastic,
};

enum class Axis : std::uint8_t { kX = 0, kY = 1 };

// The velocity components a drive holds (World::set_drive). An axis a drive does not hold is
// left to gravity, contacts and friction.
enum class DriveAxes : std::uint8_t {
  kX = 1,     // hold the x velocity only: a character controller's horizontal speed
  kY = 2,     // hold the y velocity only
  kBoth = 3,  // hold the whole velocity
};

// A stable handle: never reused within a world, unaffected by how the world stores bodies.
struct BodyId {
  static constexpr std::uint32_t kInvalid = std::numeric_limits<std::uint32_t>::max();
  std::uint32_t value = kInvalid;

  friend constexpr bool operator==(BodyId a, BodyId b) { return a.value == b.value; }
  friend constexpr bool operator!=(BodyId a, BodyId b) { return a.value != b.value; }
};

// A view of `size()` contiguous T: std::span's role for C++17 callers. Built from a pointer and a
// count, or from any container with data() and size() (std::vector, std::array, std::span); in
// C++20 it also converts to std::span. It never owns what it shows.
template <class T>
class Span {
 public:
  constexpr Span() noexcept = default;
  constexpr Span(T* data, std::size_t size) noexcept : data_(data), size_(size) {}
  template <class C, class = std::enable_if_t<
                         !std::is_same_v<std::remove_cv_t<std::remove_reference_t<C>>, Span> &&
                         std::is_convertible_v<decltype(std::declval<C&>().data()), T*>>>
  constexpr Span(C&& c) noexcept : data_(c.data()), size_(c.size()) {}  // NOLINT: implicit

  constexpr T* data() const noexcept { return data_; }
  constexpr std::size_t size() const noexcept { return size_; }
  constexpr bool empty() const noexcept { return size_ == 0; }
  constexpr T* begin() const noexcept { return data_; }
  constexpr T* end() const noexcept { return data_ + size_; }
  // i < size(); not checked.
  constexpr T& operator[](std::size_t i) const noexcept { return data_[i]; }

#if __cplusplus >= 202002L
  constexpr operator std::span<T>() const noexcept {
    return {data_, size_};
  }  // NOLINT
#endif

 private:
  T* data_ = nullptr;
  std::size_t size_ = 0;
};

// Sides on which a body was pushed during the last step (y up: bottom is the -y side).
namespace touching {
inline constexpr std::uint8_t kLeft = 1u << 0;
inline constexpr std::uint8_t kRight = 1u << 1;
inline constexpr std::uint8_t kBottom = 1u << 2;
inline constexpr std::uint8_t kTop = 1u << 3;
}  // namespace touching

// A dynamic body squeezed along `axis` between two bodies that cannot give way: `anchor` is the
// immovable body whose push reached it, `blocker` the immovable body it was pushed into.
struct CrushEvent {
  BodyId body;
  BodyId anchor;
  BodyId blocker;
  Axis axis = Axis::kX;
};

// What the last step cost and met. Counts are per step and reset by every step.
struct StepStats {
  std::uint32_t passes = 0;         // contact passes run (modern; 1 for seed2014)
  std::uint32_t contacts = 0;       // overlapping pairs found by the broadphase, all passes
  std::uint32_t resolve_calls = 0;  // pair resolutions attempted, chained ones included
  std::uint32_t max_depth = 0;      // longest chain of nested resolutions
  std::uint32_t budget_hits = 0;    // chains cut short because the work budget ran out
  std::uint32_t crush_events = 0;   // bodies squeezed between two immovable bodies
  std::uint32_t renumbered = 0;     // 1 if the step left its bodies stored in the order it reached
                                    // them, for the next steps' memory access (modern)
  std::uint32_t fast_bodies = 0;    // bodies that moved far for their size, swept (modern)
  std::uint32_t swept = 0;          // bodies whose motion continuous collision cut or slid (modern)
  // Candidate bodies the broadphase examined for all queries and pair scans of the step: the
  // solver's search work, which stays near-linear in bodies plus contacts whatever the step's
  // pushes did (saturates at 2^32 - 1).
  std::uint32_t candidates = 0;
  // 1 if the step was skipped as the fixed point it was (modern, WorldDef::skip_rest): the two
  // steps before it each left every movable body where it began them and at velocity +0, nothing
  // was changed since, and dt and the squeezes remembered were the same, so the step would have
  // rebuilt the same bits. The other counts are then the last full step's; candidates is 0.
  std::uint32_t skipped = 0;
  // Bodies of resting islands the step left out (modern, WorldDef::skip_rest): each island came
  // out of the two steps before it where it began them, at velocity +0, and nothing came near it,
  // so it would have rebuilt the same bits. The other counts are the solved bodies' only.
  std::uint32_t resting = 0;
  // 1 if the step left islands out, found that a solved body came near one (or moved one, or
  // ran out of budget), and was solved again whole: the counts are those of the whole step.
  std::uint32_t redone = 0;
  // Sub-steps the step was split into (modern): 1 unless its gravity would sink some dynamic body
  // by more than its half extent, then as many (up to 64) as keep each sub-step's sink under it.
  // The other counts are then those of all the sub-steps together.
  std::uint32_t substeps = 1;
};

// Where the last step's time went: wall time per stage of World::step, in the order the stages
// run, milliseconds (the part Box2D's b2Profile plays). Measured only while the world measures
// them (World::set_profiling); all zero otherwise.
struct StepProfile {
  double prepare = 0.0;     // bodies created or destroyed since the last step filed; flags
                            // cleared; the resting islands to leave out found (skip_rest)
  double integrate = 0.0;   // drives, gravity and motion
  double continuous = 0.0;  // continuous collision: fast bodies swept along their paths (modern)
  double contacts = 0.0;    // overlapping pairs gathered and put in order, every pass (modern)
  double chains = 0.0;      // pushes resolved along chains and walls, every pass (seed2014: all of
                            // its resolution, which gathers as it goes)
  double velocity = 0.0;    // the velocity rule
  double friction = 0.0;    // friction (modern, rough bodies only)
  double layout = 0.0;      // the check after a step that left islands out, and the islands
                            // filed for the next (skip_rest); the step's report filed; bodies
                            // renumbered in reach order (modern); a step skipped whole
  double total = 0.0;       // the whole step: the stages and the little between them
};

// The stages of a StepProfile as a table, in step order (total excluded): what a profile's
// readers print.
struct StepStage {
  const char* name;
  double StepProfile::*ms;
};
inline constexpr StepStage kStepStages[] = {
    {"prepare", &StepProfile::prepare},       {"integrate", &StepProfile::integrate},
    {"continuous", &StepProfile::continuous}, {"contacts", &StepProfile::contacts},
    {"chains", &StepProfile::chains},         {"velocity", &StepProfile::velocity},
    {"friction", &StepProfile::friction},     {"layout", &StepProfile::layout},
};

}  // namespace chain
