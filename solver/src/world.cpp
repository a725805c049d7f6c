// SPDX-License-Identifier: MIT
#include "world_impl.h"

#include "buffer.h"

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
  detail::push_buffer(impl_->origin_of_id, detail::origin_of(def));
  detail::push_buffer(impl_->slot_of_id, impl_->bodies.size());
  impl_->bodies.append(def, id);
  if (def.friction > 0.0) ++impl_->rough_bodies;
  if (def.type == BodyType::kDynamic) {
    impl_->sink_rate = std::max(
        impl_->sink_rate, detail::sink_rate(impl_->def.gravity, impl_->bodies.gravity_scale.back(),
                                            def.half_extents));
  }
  impl_->dirty = true;
  impl_->rest.disturb();
  if (!impl_->sorted_once || def.type != BodyType::kDynamic ||
      impl_->def.variant != Variant::kModern)
    impl_->full = true;
  return BodyId{id};
}

void World::destroy_body(BodyId id) {
  Impl& w = *impl_;
  const std::uint32_t s = w.slot(id);
  w.rest.disturb();
  w.islands.wake(s);
  if (w.bodies.friction[s] > 0.0) --w.rough_bodies;
  if (w.bodies.type[s] == BodyType::kDynamic &&
      detail::sink_rate(w.def.gravity, w.bodies.gravity_scale[s],
                        {w.bodies.hx(s), w.bodies.hy(s)}) >= w.sink_rate) {
    w.sink_stale = true;
  }
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
  impl_->rest.disturb();
  impl_->islands.wake(s);
  impl_->bodies.driven[s] = held;
  impl_->bodies.drive_x[s] = (held & detail::kDriveX) ? velocity.x : 0.0;
  impl_->bodies.drive_y[s] = (held & detail::kDriveY) ? velocity.y : 0.0;
}

void World::clear_drive(BodyId id) {
  const std::uint32_t s = impl_->slot(id);
  impl_->rest.disturb();
  impl_->islands.wake(s);
  impl_->bodies.driven[s] = 0;
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
  impl_->rest.disturb();
  impl_->islands.wake(s);
  impl_->bodies.vx[s] = velocity.x;
  impl_->bodies.vy[s] = velocity.y;
}

void World::step(double dt) {
  if (!std::isfinite(dt) || dt <= 0.0) {
    throw std::invalid_argument("step: dt must be finite and > 0, got " + number(dt));
  }
  Impl& w = *impl_;
  std::uint32_t n = 1;
  if (w.def.variant == Variant::kModern) {
    if (w.sink_stale) {
      w.sink_rate = 0.0;
      for (std::uint32_t i = 0; i < w.bodies.size(); ++i) {
        if (w.bodies.type[i] != BodyType::kDynamic || w.bodies.dead(i)) continue;
        w.sink_rate =
            std::max(w.sink_rate, detail::sink_rate(w.def.gravity, w.bodies.gravity_scale[i],
                                                    {w.bodies.hx(i), w.bodies.hy(i)}));
      }
      w.sink_stale = false;
    }
    n = detail::substep_count(dt, w.sink_rate);
  }
  if (n == 1) {
    w.step_once(dt, false);
    return;
  }
  // Sub-steps (substeps.h): each of dt / n; the step reports all of them together. A drive sets
  // velocities at the start of the step only, as world.h says: in the later sub-steps a driven
  // body keeps what the earlier ones left it (a character controller that sets a speed once a
  // frame sees the same), its drive's values stood in for by its velocity meanwhile.
  const double part = dt / n;
  StepStats stats;
  StepProfile profile;
  bool solved = false;  // some sub-step was solved (not skipped at rest)
  w.carried_crushes.clear();
  w.held_drives.clear();
  for (std::uint32_t i = 0; i < w.bodies.size(); ++i) {
    if (w.bodies.driven[i] != 0)
      w.held_drives.push_back({w.bodies.id[i], w.bodies.drive_x[i], w.bodies.drive_y[i]});
  }
  for (std::uint32_t k = 0; k < n; ++k) {
    if (k > 0) {
      w.carried_touch.assign(w.bodies.touching.begin(), w.bodies.touching.end());
      for (const Impl::HeldDrive& d : w.held_drives) {
        const std::uint32_t s = w.slot_of_id[d.id];
        if (w.bodies.driven[s] & detail::kDriveX) w.bodies.drive_x[s] = w.bodies.vx[s];
        if (w.bodies.driven[s] & detail::kDriveY) w.bodies.drive_y[s] = w.bodies.vy[s];
      }
    }
    w.step_once(part, k > 0);
    // A skipped sub-step reports the last solved one's counts: they are not counted again.
    if (w.stats.skipped == 0) {
      if (!solved) {
        stats = w.stats;
      } else {
        detail::add_substep(stats, w.stats);
      }
      solved = true;
    }
    detail::add_substep(profile, w.profile);
    w.carried_crushes.insert(w.carried_crushes.end(), w.crushes.begin(), w.crushes.end());
  }
  for (const Impl::HeldDrive& d : w.held_drives) {
    const std::uint32_t s = w.slot_of_id[d.id];
    w.bodies.drive_x[s] = d.x;
    w.bodies.drive_y[s] = d.y;
  }
  // A crush reported by several sub-steps (the same body, anchor, blocker and axis) is reported
  // once, in the order of its first report.
  w.crushes.clear();
  for (const CrushEvent& e : w.carried_crushes) {
    const bool seen = std::any_of(w.crushes.begin(), w.crushes.end(), [&](const CrushEvent& c) {
      return c.body == e.body && c.anchor == e.anchor && c.blocker == e.blocker && c.axis == e.axis;
    });
    if (!seen) w.crushes.push_back(e);
  }
  if (!solved) stats = w.stats;  // every sub-step skipped: the last solved step's report stands
  stats.crush_events = static_cast<std::uint32_t>(w.crushes.size());
  stats.substeps = n;
  w.stats = stats;
  w.profile = profile;
}

// The step as a list of stages (world.h's numbered list), each in its own file; the clock laps
// each into the StepProfile when profiling.
void World::Impl::step_once(double dt, bool carry) {
  Impl& w = *this;
  detail::StageClock clock(w.profiling);
  w.profile = StepProfile{};
  const bool modern = w.def.variant == Variant::kModern;
  const bool resting = modern && w.def.skip_rest;
  // A skipped step hands the layout the last solved step's reach order: that of the whole world.
  if (resting && !w.dirty && w.rest.may_skip(dt, w.modern.remembers_squeezes()) &&
      !(w.last_partial && w.layout.due_next())) {
    w.skip_step();
    clock.lap(w.profile.layout);
    w.profile.total = clock.total();
    return;
  }
  w.prepare();
  const std::uint64_t examined = w.broadphase.examined();
  // Resting islands are left out (islands.h) but in the steps the layout may renumber after.
  const bool partial = resting && w.islands.plan(w.bodies, w.broadphase, w.def.gravity, dt,
                                                 w.def.touch_tolerance, w.layout.due_next());
  const std::span<const detail::SlotRun> runs = w.islands.runs();
  w.clear_touching(partial ? &runs : nullptr);
  if (partial) {
    w.islands.save(w.bodies);
    w.modern.mark();
  }
  clock.lap(w.profile.prepare);
  w.solve(dt, partial, clock);
  if (partial) w.islands.touch_statics(w.bodies);  // before settle() wakes any
  if (resting) {
    const bool cut = w.stats.budget_hits > 0;
    if (!w.islands.settle(w.bodies, w.broadphase, w.modern, w.motion.fast(), w.crush_records, cut,
                          w.def.gravity, dt, w.def.touch_tolerance)) {
      // A body came near an island left out: the step again, solving every body.
      w.islands.undo(w.bodies);
      w.modern.undo();
      w.clear_records();
      w.clear_touching(nullptr);
      w.solve(dt, false, clock);
      w.stats.redone = 1;
      w.islands.settle(w.bodies, w.broadphase, w.modern, w.motion.fast(), w.crush_records,
                       w.stats.budget_hits > 0, w.def.gravity, dt, w.def.touch_tolerance);
      w.last_partial = false;
    } else if (partial) {
      w.modern.keep();
      w.last_partial = true;
    } else {
      w.last_partial = false;
    }
  }
  if (carry) {
    for (std::size_t i = 0; i < carried_touch.size(); ++i)
      detail::add_touch(w.bodies.touching[i], static_cast<std::uint8_t>(carried_touch[i]));
  }
  w.file_report(examined);
  if (modern) {
    if (w.def.skip_rest) w.rest.after_step(w.bodies, dt);
    w.renumber_if_due();
  }
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
