// SPDX-License-Identifier: MIT
// Body storage: structure of arrays in solve order.
//
// Solve order is the order every loop of a step follows. It is derived from the bodies
// themselves (kind, then place along a Z-order curve, then size and the rest), never from
// creation order, so that a scene built in any order gives the same bits, and bodies close in
// space are close in memory. Dynamic bodies come first, then kinematic, then
// static, which lets hot loops run over plain index ranges. Later the modern resolver's own
// walk may renumber the dynamic bodies (layout.h), which depends on the bodies alone too.
#pragma once

#include <chain/types.h>
#include <chain/world.h>

#include "buffer.h"

#include <cstdint>
#include <cstring>
#include <span>
#include <type_traits>
#include <vector>

namespace chain::detail {

inline constexpr std::uint32_t kNoSlot = 0xffffffffu;

struct Point {
  double x, y;
};

// Bits of Bodies::driven: the velocity components a drive holds (chain::DriveAxes values).
inline constexpr std::uint8_t kDriveX = 1u;
inline constexpr std::uint8_t kDriveY = 2u;

// A body's touching:: bits. A type of its own rather than std::uint8_t: a store through a
// character type may alias any object, and after each of the two the walls' loop makes for every
// push, the compiler reloaded every vector's data pointer it had read.
enum class TouchBits : std::uint8_t {};
inline void add_touch(TouchBits& t, std::uint8_t bits) {
  t = static_cast<TouchBits>(static_cast<std::uint8_t>(t) | bits);
}

// What a body was created as, beyond what Bodies keeps of it unchanged (size, mass, kind...):
// its first centre and velocity. Only the canonical sort reads it, to break a tie between two
// bodies whose states have become identical without ids (creation order) deciding.
struct Origin {
  double cx, cy, vx, vy;
};
Origin origin_of(const BodyDef& def);

struct Bodies {
  // Centre and half extents together: every overlap test reads all four, and a chain reaches
  // bodies in no fixed order, so one cache line per body beats four.
  struct Box {
    double center[2];
    double half[2];
  };
  std::vector<Box> box;
  std::vector<double> vx, vy;  // velocity
  std::vector<double> mass;    // 0 for kinematic and static bodies
  std::vector<double> gravity_scale;
  std::vector<double> restitution;
  std::vector<double> friction;
  std::vector<double> drive_x, drive_y;
  std::vector<std::uint8_t> driven;  // kDriveX | kDriveY bits held by the body's drive
  // Movable bodies: the centre at the start of the current step, before integration. Which face
  // a body came in through, and the path a fast body swept, are read from it.
  std::vector<Point> start;
  std::vector<TouchBits> touching;  // touching:: bits of the last step
  std::vector<BodyType> type;
  std::vector<std::uint32_t> id;  // BodyId value of each slot
  // BodyDef::category_bits in the low 16 bits and mask_bits in the high 16: one load a body.
  // Empty while every body has the defaults (category 1, mask 0xFFFF: all collide), so a world
  // that filters nothing holds nothing for it.
  std::vector<std::uint32_t> filter;
  static constexpr std::uint32_t kNoFilter = 0xFFFF0001u;
  // BodyDef::surface_velocity: empty while no body has one, as filter.
  std::vector<Point> surface;

  // Valid after canonicalize(): slots [0, dynamic_end) are dynamic, [dynamic_end, movable_end)
  // kinematic and the rest static.
  std::uint32_t dynamic_end = 0;
  std::uint32_t movable_end = 0;
  // Valid after canonicalize(): some body has a restitution above 0 (the velocity rule bounces).
  bool bounces = false;

  std::uint32_t size() const { return static_cast<std::uint32_t>(box.size()); }
  double x(std::uint32_t i) const { return box[i].center[0]; }
  double y(std::uint32_t i) const { return box[i].center[1]; }
  double hx(std::uint32_t i) const { return box[i].half[0]; }
  double hy(std::uint32_t i) const { return box[i].half[1]; }
  double& pos(int axis, std::uint32_t i) { return box[i].center[axis]; }
  double pos(int axis, std::uint32_t i) const { return box[i].center[axis]; }
  double half(int axis, std::uint32_t i) const { return box[i].half[axis]; }
  // Centre at the start of the step along axis (a static body's never changes).
  double start_pos(int axis, std::uint32_t i) const {
    return i < movable_end ? (axis == 0 ? start[i].x : start[i].y) : box[i].center[axis];
  }
  bool immovable(std::uint32_t i) const { return i >= dynamic_end; }
  // Whether bodies i and j collide: each one's category is in the other's mask (BodyDef).
  bool collides(std::uint32_t i, std::uint32_t j) const {
    if (filter.empty()) return true;
    const std::uint32_t a = filter[i], b = filter[j];
    return (a & (b >> 16)) != 0 && (b & (a >> 16)) != 0;
  }

  // The id of a slot whose body was destroyed in place (kill()): a dynamic slot with no body,
  // whose centre is NaN, so that it overlaps nothing, and that gravity and drives leave alone.
  static constexpr std::uint32_t kDeadId = 0xffffffffu;
  bool dead(std::uint32_t i) const { return id[i] == kDeadId; }

  // fn(v) for every per-slot array above, in one fixed order: the one list of them that moving,
  // dropping and truncating slots go through, so that a new array cannot be left out of one.
  template <class Fn>
  void each_array(Fn&& fn) {
    fn(box), fn(vx), fn(vy), fn(mass), fn(gravity_scale), fn(restitution), fn(friction);
    fn(drive_x), fn(drive_y), fn(driven), fn(start), fn(touching), fn(type), fn(id);
    if (!filter.empty()) fn(filter);
    if (!surface.empty()) fn(surface);
  }

  void append(const BodyDef& def, std::uint32_t body_id);
  // Empties dynamic slot `slot` in place (see kDeadId); no other slot moves.
  void kill(std::uint32_t slot);
  // Slot `to` takes everything slot `from` holds (from is left as it was).
  void move_slot(std::uint32_t from, std::uint32_t to);
  // Keeps slots [0, n) and drops the rest.
  void truncate(std::uint32_t n);
  // Drops every dead slot, keeping the others in order.
  void drop_dead();
  // Sorts `slots` by the canonical key without its place along the Z-order curve: by what the
  // bodies are now and were created as, never by creation order (origin_of_id as canonicalize's).
  void sort_by_state(std::span<std::uint32_t> slots, std::span<const Origin> origin_of_id) const;
  // Moves the last slot into `slot` and drops the last; returns the id now stored at `slot`.
  std::uint32_t swap_remove(std::uint32_t slot);
  // Sorts slots into solve order; fills slot_of_id (indexed by BodyId value). origin_of_id, by
  // BodyId value too, breaks ties between bodies whose fields are all equal.
  void canonicalize(std::vector<std::uint32_t>& slot_of_id, std::span<const Origin> origin_of_id);

  // One buffer, as large as the widest per-slot array, that permute() copies each array through in
  // turn and keeps between calls, so that it allocates nothing: 32 bytes a body, where a buffer
  // per element type held 63.
  class Spare {
   public:
    void reserve(std::size_t n) { raw_.reserve(n); }
    // v[i] takes the old v[order[i]] for every i (order is a permutation of v's indices).
    template <class T>
    void gather(std::vector<T>& v, std::span<const std::uint32_t> order) {
      static_assert(std::is_trivially_copyable_v<T> && sizeof(T) <= sizeof(Box));
      if (raw_.size() < order.size()) resize_buffer(raw_, order.size());
      auto* const out = reinterpret_cast<unsigned char*>(raw_.data());
      for (std::size_t i = 0; i < order.size(); ++i)
        std::memcpy(out + i * sizeof(T), &v[order[i]], sizeof(T));
      if (!order.empty()) std::memcpy(v.data(), out, order.size() * sizeof(T));
    }

   private:
    std::vector<Box> raw_;
  };
  // Slot i takes what slot order[i] held, for every i (order is a permutation of the slots).
  void permute(std::span<const std::uint32_t> order, Spare& spare);
};

}  // namespace chain::detail
