// SPDX-License-Identifier: MIT
#include <chain/world.h>

#include "bodies.h"
#include "broadphase.h"
#include "chain_resolver.h"
#include "friction.h"
#include "layout.h"
#include "motion.h"
#include "seed2014_resolver.h"
#include "stage_clock.h"
#include "step_context.h"
#include "validate.h"
#include "velocity_response.h"
#include "worker_pool.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace chain {

using detail::check_range;
using detail::number;

struct World::Impl {
  WorldDef def;
  detail::Bodies bodies;
  std::vector<std::uint32_t> slot_of_id;      // indexed by BodyId value; kNoSlot once destroyed
  std::vector<std::uint32_t> creation_order;  // dynamic slots, oldest first
  // By BodyId value, destroyed ones included (as slot_of_id): the canonical sort's tie-break.
  std::vector<detail::Origin> origin_of_id;
  // Bodies created or destroyed since the last step: prepare() files them. `full` when that
  // takes the canonical re-sort (anything but dynamic bodies created into and destroyed from an
  // already sorted modern world).
  bool dirty = false;
  bool full = false;
  bool sorted_once = false;           // canonicalize() has run: the world has a canonical order
  std::uint32_t committed = 0;        // slots before those created since the last step
  std::vector<std::uint32_t> empty;   // dead dynamic slots (Bodies::kill), for created bodies
  std::vector<std::uint32_t> placed;  // place_created()'s buffer
  detail::Broadphase broadphase;
  detail::VelocityResponse response;
  detail::Motion motion;
  detail::Friction friction;
  std::size_t rough_bodies = 0;  // bodies with friction > 0: friction runs only while there are
  detail::ChainResolver modern;
  detail::Seed2014Resolver seed2014;
  detail::Layout layout;
  StepStats stats;
  std::vector<detail::CrushRecord> crush_records;
  std::vector<CrushEvent> crushes;
  detail::WorkerPool pool;  // def.threads - 1 workers
  bool profiling = false;
  StepProfile profile;

  std::uint32_t slot(BodyId id) const {
    if (id.value >= slot_of_id.size() || slot_of_id[id.value] == detail::kNoSlot) {
      throw std::invalid_argument("no body with id " + std::to_string(id.value) + " in this world");
    }
    return slot_of_id[id.value];
  }

  void canonicalize() {
    bodies.drop_dead();
    empty.clear();
    bodies.canonicalize(slot_of_id, origin_of_id);
    committed = bodies.size();
    sorted_once = true;
    broadphase.configure(bodies);
    layout.reset(bodies.size());
    response.reserve(bodies.size());
    list_creation_order();
    dirty = false;
  }

  void list_creation_order() {
    creation_order.clear();
    for (const std::uint32_t s : slot_of_id) {
      if (s != detail::kNoSlot && s < bodies.dynamic_end) creation_order.push_back(s);
    }
  }

  std::uint32_t live() const { return bodies.size() - static_cast<std::uint32_t>(empty.size()); }

  // Whether a destroyed body can leave its slot empty (no other slot moves, nothing re-sorted).
  bool kill_in_place(std::uint32_t s) const {
    return sorted_once && !full && def.variant == Variant::kModern && s < committed &&
           bodies.type[s] == BodyType::kDynamic;
  }

  // The dynamic bodies created since the last step take empty slots: sorted among themselves by
  // what they are (never by creation order), into the empty slots in ascending order, each filed
  // in the broadphase as a body filed again is. False (nothing changed) when there are not enough
  // empty slots or a body is larger than every broadphase level's: canonicalize() then.
  bool place_created() {
    const std::uint32_t n = bodies.size();
    if (n - committed > empty.size()) return false;
    placed.clear();
    for (std::uint32_t p = committed; p < n; ++p) {
      if (!broadphase.fits(std::max(bodies.hx(p), bodies.hy(p)))) return false;
      placed.push_back(p);
    }
    bodies.sort_by_state(placed, origin_of_id);
    std::sort(empty.begin(), empty.end());
    for (std::size_t k = 0; k < placed.size(); ++k) {
      bodies.move_slot(placed[k], empty[k]);
      slot_of_id[bodies.id[empty[k]]] = empty[k];
      if (bodies.restitution[empty[k]] > 0.0) bodies.bounces = true;
    }
    bodies.truncate(committed);
    for (std::size_t k = 0; k < placed.size(); ++k)
      broadphase.insert(bodies, empty[k]);
    empty.erase(empty.begin(), empty.begin() + static_cast<std::ptrdiff_t>(placed.size()));
    return true;
  }

  // Files bodies created or destroyed since the last step and clears the last step's records.
  void prepare() {
    if (dirty) {
      if (full || !place_created()) canonicalize();
      dirty = full = false;
    }
    stats = StepStats{};
    crush_records.clear();
    response.clear();
    std::fill(bodies.touching.begin(), bodies.touching.end(), detail::TouchBits{});
  }

  // The step's counts and crush events, for last_step_stats() and crush_events().
  void file_report(std::uint64_t examined_before) {
    stats.candidates = static_cast<std::uint32_t>(
        std::min<std::uint64_t>(broadphase.examined() - examined_before, 0xffffffffu));
    crushes.clear();
    for (const detail::CrushRecord& r : crush_records) {
      crushes.push_back({BodyId{bodies.id[r.body]}, BodyId{bodies.id[r.anchor]},
                         BodyId{bodies.id[r.blocker]}, r.axis});
    }
  }

  // Stores the bodies in the order the step reached them, when the layout says it pays (modern).
  void renumber_if_due() {
    if (!layout.due()) return;  // the jumps are counted only when a renumbering may follow
    const std::span<const std::uint32_t> order =
        layout.plan(bodies, modern.reach_order(), modern.reach_jumps());
    if (!order.empty()) {
      renumber(order);
      stats.renumbered = 1;
    }
  }

  // Slot i takes the body of slot order[i]; everything that names slots follows.
  void renumber(std::span<const std::uint32_t> order) {
    bodies.permute(order, layout.spare());
    empty.clear();
    for (std::uint32_t i = 0; i < bodies.size(); ++i) {
      if (bodies.dead(i)) {
        empty.push_back(i);
      } else {
        slot_of_id[bodies.id[i]] = i;
      }
    }
    list_creation_order();
    broadphase.renumber(order);
    modern.forget_slots();
  }
};

World::World(const WorldDef& def) : impl_(std::make_unique<Impl>()) {
  if (std::string e = validate(def); !e.empty()) throw std::invalid_argument("WorldDef: " + e);
  impl_->def = def;
  impl_->pool.reset(def.threads);
}

World::~World() = default;
World::World(const World& other) : impl_(std::make_unique<Impl>(*other.impl_)) {}
World& World::operator=(const World& other) {
  if (this != &other) impl_ = std::make_unique<Impl>(*other.impl_);
  return *this;
}
World::World(World&& other) noexcept = default;
World& World::operator=(World&& other) noexcept = default;

BodyId World::create_body(const BodyDef& def) {
  if (std::string e = validate(def); !e.empty()) throw std::invalid_argument("BodyDef: " + e);
  const auto id = static_cast<std::uint32_t>(impl_->slot_of_id.size());
  if (id == BodyId::kInvalid) throw std::length_error("a world holds at most 2^32 - 1 bodies");
  impl_->origin_of_id.push_back(detail::origin_of(def));
  impl_->slot_of_id.push_back(impl_->bodies.size());
  impl_->bodies.append(def, id);
  if (def.friction > 0.0) ++impl_->rough_bodies;
  impl_->dirty = true;
  if (!impl_->sorted_once || def.type != BodyType::kDynamic ||
      impl_->def.variant != Variant::kModern)
    impl_->full = true;
  return BodyId{id};
}

void World::destroy_body(BodyId id) {
  Impl& w = *impl_;
  const std::uint32_t s = w.slot(id);
  if (w.bodies.friction[s] > 0.0) --w.rough_bodies;
  w.slot_of_id[id.value] = detail::kNoSlot;
  if (w.kill_in_place(s)) {
    w.bodies.kill(s);
    w.broadphase.remove(s);
    w.empty.push_back(s);
    return;
  }
  const std::uint32_t moved = w.bodies.swap_remove(s);
  if (moved != detail::kNoSlot) w.slot_of_id[moved] = s;
  w.dirty = w.full = true;
}

bool World::contains(BodyId id) const noexcept {
  return id.value < impl_->slot_of_id.size() && impl_->slot_of_id[id.value] != detail::kNoSlot;
}

std::size_t World::body_count() const noexcept {
  return impl_->live();
}

void World::set_drive(BodyId id, Vec2 velocity, DriveAxes axes) {
  const std::uint32_t s = impl_->slot(id);
  if (impl_->bodies.type[s] == BodyType::kStatic) {
    throw std::invalid_argument("a static body cannot be driven");
  }
  const auto held = static_cast<std::uint8_t>(axes);
  if (axes != DriveAxes::kX && axes != DriveAxes::kY && axes != DriveAxes::kBoth) {
    throw std::invalid_argument("drive axes must be x, y or both, got " + std::to_string(held));
  }
  std::string e;
  if (held & detail::kDriveX)
    e += check_range("drive velocity.x", velocity.x, -kMaxSpeed, kMaxSpeed, "within +-1e6 m/s");
  if (held & detail::kDriveY)
    e += check_range("drive velocity.y", velocity.y, -kMaxSpeed, kMaxSpeed, "within +-1e6 m/s");
  if (!e.empty()) throw std::invalid_argument(e);
  impl_->bodies.driven[s] = held;
  impl_->bodies.drive_x[s] = (held & detail::kDriveX) ? velocity.x : 0.0;
  impl_->bodies.drive_y[s] = (held & detail::kDriveY) ? velocity.y : 0.0;
}

void World::clear_drive(BodyId id) {
  impl_->bodies.driven[impl_->slot(id)] = 0;
}

void World::set_velocity(BodyId id, Vec2 velocity) {
  const std::uint32_t s = impl_->slot(id);
  if (impl_->bodies.type[s] == BodyType::kStatic) {
    throw std::invalid_argument("a static body cannot have a velocity");
  }
  if (std::string e =
          check_range("velocity.x", velocity.x, -kMaxSpeed, kMaxSpeed, "within +-1e6 m/s") +
          check_range("velocity.y", velocity.y, -kMaxSpeed, kMaxSpeed, "within +-1e6 m/s");
      !e.empty()) {
    throw std::invalid_argument(e);
  }
  impl_->bodies.vx[s] = velocity.x;
  impl_->bodies.vy[s] = velocity.y;
}

Vec2 World::position(BodyId id) const {
  const std::uint32_t s = impl_->slot(id);
  return {impl_->bodies.x(s), impl_->bodies.y(s)};
}

Vec2 World::velocity(BodyId id) const {
  const std::uint32_t s = impl_->slot(id);
  return {impl_->bodies.vx[s], impl_->bodies.vy[s]};
}

std::uint8_t World::touching_flags(BodyId id) const {
  return static_cast<std::uint8_t>(impl_->bodies.touching[impl_->slot(id)]);
}

void World::read_state(Span<const BodyId> ids, Span<Vec2> positions, Span<Vec2> velocities) const {
  const detail::Bodies& b = impl_->bodies;
  if ((!positions.empty() && positions.size() < ids.size()) ||
      (!velocities.empty() && velocities.size() < ids.size())) {
    throw std::invalid_argument("read_state: an output span is shorter than ids");
  }
  for (std::size_t k = 0; k < ids.size(); ++k) {
    const std::uint32_t s = impl_->slot(ids[k]);
    if (!positions.empty()) positions[k] = {b.x(s), b.y(s)};
    if (!velocities.empty()) velocities[k] = {b.vx[s], b.vy[s]};
  }
}

// Entry k of read_all's outputs is the k-th slot that holds a body: dead slots (Bodies::kill)
// are passed over, so that a world with none costs one test a slot.
void World::read_all(Span<BodyId> ids, Span<Vec2> positions, Span<Vec2> velocities) const {
  const detail::Bodies& b = impl_->bodies;
  const std::size_t n = impl_->live();
  if ((!ids.empty() && ids.size() < n) || (!positions.empty() && positions.size() < n) ||
      (!velocities.empty() && velocities.size() < n)) {
    throw std::invalid_argument("read_all: an output span is shorter than body_count()");
  }
  std::size_t k = 0;
  for (std::uint32_t s = 0; s < b.size(); ++s) {
    if (b.dead(s)) continue;
    if (!ids.empty()) ids[k] = BodyId{b.id[s]};
    if (!positions.empty()) positions[k] = {b.box[s].center[0], b.box[s].center[1]};
    if (!velocities.empty()) velocities[k] = {b.vx[s], b.vy[s]};
    ++k;
  }
}

void World::update_all(Span<BodyId> ids, Span<Vec2> positions, Span<Vec2> velocities,
                       std::vector<std::uint32_t>& changed) const {
  const detail::Bodies& b = impl_->bodies;
  const std::size_t n = impl_->live();
  if (ids.size() < n || positions.size() < n || velocities.size() < n) {
    throw std::invalid_argument("update_all: an output span is shorter than body_count()");
  }
  changed.clear();
  auto same = [](double a, double c) {
    return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(c) && a == a;
  };
  std::uint32_t k = 0;
  for (std::uint32_t s = 0; s < b.size(); ++s) {
    if (b.dead(s)) continue;
    const Vec2 p{b.box[s].center[0], b.box[s].center[1]}, v{b.vx[s], b.vy[s]};
    if (!(ids[k].value == b.id[s] && same(p.x, positions[k].x) && same(p.y, positions[k].y) &&
          same(v.x, velocities[k].x) && same(v.y, velocities[k].y))) {
      ids[k] = BodyId{b.id[s]};
      positions[k] = p;
      velocities[k] = v;
      changed.push_back(k);
    }
    ++k;
  }
}

// The step as a list of stages (world.h's numbered list), each in its own file; the clock laps
// each into the StepProfile when profiling.
void World::step(double dt) {
  if (!std::isfinite(dt) || dt <= 0.0) {
    throw std::invalid_argument("step: dt must be finite and > 0, got " + number(dt));
  }
  Impl& w = *impl_;
  detail::StageClock clock(w.profiling);
  w.profile = StepProfile{};
  w.prepare();
  clock.lap(w.profile.prepare);

  const std::uint64_t examined = w.broadphase.examined();
  const bool modern = w.def.variant == Variant::kModern;
  const bool rough = modern && w.rough_bodies > 0;
  w.motion.integrate(w.bodies, w.broadphase, w.def.gravity, dt, modern, rough, w.pool);
  clock.lap(w.profile.integrate);

  const std::uint64_t budget = static_cast<std::uint64_t>(w.def.budget_per_body) * w.live() + 1024u;
  detail::StepContext ctx{
      w.bodies, w.broadphase, w.response,
      w.def,    w.stats,      w.crush_records,
      budget,   w.motion,     w.def.velocity_rule == VelocityRule::kInelastic || rough,
      modern,   w.pool,       clock,
      w.profile};
  if (modern) {
    w.modern.resolve(ctx);  // laps sweep, contacts and chains itself
  } else {
    w.seed2014.resolve(ctx, w.creation_order);
    clock.lap(w.profile.chains);
  }

  if (w.def.velocity_rule == VelocityRule::kInelastic) {
    w.response.apply(w.bodies, w.def.restitution_threshold, w.pool);
  }
  clock.lap(w.profile.velocity);

  if (rough)
    w.friction.apply(w.bodies, w.broadphase, w.response.links(), w.motion.pre_velocity, dt);
  clock.lap(w.profile.friction);

  w.file_report(examined);
  if (modern) w.renumber_if_due();
  clock.lap(w.profile.layout);
  w.profile.total = clock.total();
}

const StepStats& World::last_step_stats() const noexcept {
  return impl_->stats;
}
void World::set_profiling(bool on) noexcept {
  impl_->profiling = on;
}
const StepProfile& World::last_step_profile() const noexcept {
  return impl_->profile;
}
Span<const CrushEvent> World::crush_events() const noexcept {
  return {impl_->crushes.data(), impl_->crushes.size()};
}
const WorldDef& World::def() const noexcept {
  return impl_->def;
}

}  // namespace chain
