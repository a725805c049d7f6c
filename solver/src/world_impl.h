// SPDX-License-Identifier: MIT
// What a World holds: its bodies, the stages that step them and what the last step reported,
// shared by the files that implement World (world.cpp steps and changes it, world_state.cpp
// reads it).
#pragma once

#include <chain/world.h>

#include "bodies.h"
#include "broadphase.h"
#include "chain_resolver.h"
#include "friction.h"
#include "islands.h"
#include "layout.h"
#include "motion.h"
#include "rest.h"
#include "seed2014_resolver.h"
#include "stage_clock.h"
#include "step_context.h"
#include "substeps.h"
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
  // The largest detail::sink_rate of the dynamic bodies (modern), for sub-steps; `sink_stale`
  // when the body that had it was destroyed (found again at the next step).
  double sink_rate = 0.0;
  bool sink_stale = false;
  std::vector<detail::TouchBits> carried_touch;  // touching flags of the step's earlier sub-steps
  std::vector<CrushEvent> carried_crushes;       // and its crush events
  struct HeldDrive {
    std::uint32_t id;  // BodyId value
    double x, y;       // the drive's velocity components, m/s
  };
  std::vector<HeldDrive> held_drives;  // the drives of a sub-stepped step, while stood in for
  detail::ChainResolver modern;
  detail::Seed2014Resolver seed2014;
  detail::Layout layout;
  detail::Rest rest;
  detail::Islands islands;
  bool last_partial = false;  // the last solved step left resting islands out (islands.h)
  StepStats stats;
  std::vector<detail::CrushRecord> crush_records;
  std::vector<CrushEvent> crushes;
  detail::WorkerPool pool;  // def.threads - 1 workers
  bool profiling = false;
  StepProfile profile;

  // Resting islands are left out of steps (islands.h): modern, skip_rest.
  bool keeps_islands() const { return def.variant == Variant::kModern && def.skip_rest; }

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
    islands.reset(keeps_islands() ? bodies.size() : 0);
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
    for (std::size_t k = 0; k < placed.size(); ++k) {
      broadphase.insert(bodies, empty[k]);
      islands.wake(empty[k]);
    }
    empty.erase(empty.begin(), empty.begin() + static_cast<std::ptrdiff_t>(placed.size()));
    return true;
  }

  // One step (or sub-step) of dt; `carry`: OR the touching flags of carried_touch into the
  // step's (a later sub-step).
  void step_once(double dt, bool carry);

  // Files bodies created or destroyed since the last step and clears the last step's records.
  void prepare() {
    if (dirty) {
      if (full || !place_created()) canonicalize();
      dirty = full = false;
    }
    clear_records();
  }
  void clear_records() {
    stats = StepStats{};
    crush_records.clear();
    response.clear();
  }
  // The touching flags of the bodies the step solves (`runs`; null: every body).
  void clear_touching(const std::span<const detail::SlotRun>* runs) {
    if (runs == nullptr) {
      std::fill(bodies.touching.begin(), bodies.touching.end(), detail::TouchBits{});
      return;
    }
    for (const detail::SlotRun& r : *runs)
      std::fill(bodies.touching.begin() + r.begin, bodies.touching.begin() + r.end,
                detail::TouchBits{});
    // Static bodies are never left out.
    std::fill(bodies.touching.begin() + bodies.movable_end, bodies.touching.end(),
              detail::TouchBits{});
  }

  // Integration, resolution and velocities for one step: of every body, or (`partial`) of those
  // the islands plan left in.
  void solve(double dt, bool partial, detail::StageClock& clock) {
    const bool modern_variant = def.variant == Variant::kModern;
    const bool rough = modern_variant && rough_bodies > 0;
    const std::span<const detail::SlotRun> runs = islands.runs();
    motion.integrate(bodies, broadphase, def.gravity, dt, modern_variant, rough, pool,
                     partial ? &runs : nullptr);
    const bool resting = modern_variant && def.skip_rest;
    detail::Reach* const reach = resting ? islands.begin_reach(bodies) : nullptr;
    clock.lap(profile.integrate);

    std::uint64_t budget = static_cast<std::uint64_t>(def.budget_per_body) * live() + 1024u;
    // The islands left out spent this much when last solved: a step that solved them too would
    // have as much less left for the others.
    if (partial) budget -= std::min(budget, islands.skipped_spend());
    detail::StepContext ctx{bodies,
                            broadphase,
                            response,
                            def,
                            stats,
                            crush_records,
                            budget,
                            motion,
                            def.velocity_rule == VelocityRule::kInelastic || rough,
                            modern_variant,
                            pool,
                            clock,
                            profile,
                            dt};
    if (resting) {
      ctx.reach = reach;
      ctx.spent = islands.spent();
      ctx.skipped = partial ? islands.skipped() : nullptr;
      stats.resting = partial ? islands.skipped_bodies() : 0;
    }
    if (modern_variant) {
      modern.resolve(ctx);  // laps continuous, contacts and chains itself
    } else {
      seed2014.resolve(ctx, creation_order);
      clock.lap(profile.chains);
    }

    if (def.velocity_rule == VelocityRule::kInelastic) {
      response.apply(bodies, def.restitution_threshold, pool);
    }
    clock.lap(profile.velocity);

    if (rough) {
      friction.apply(bodies, broadphase, response.links(), motion.pre_velocity, dt,
                     def.touch_tolerance, reach);
    }
    clock.lap(profile.friction);
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
      rest.disturb();  // the same bodies, but solved in another order
    }
  }

  // A step at rest (detail::Rest): the last solved step's report stands, and the layout counts
  // the step, with that step's reach order, as a solved one would.
  void skip_step() {
    stats.renumbered = 0;
    stats.candidates = 0;
    stats.skipped = 1;
    renumber_if_due();
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
    broadphase.renumber(order, layout.spare());
    modern.forget_slots();
    islands.reset(keeps_islands() ? bodies.size() : 0);
  }
};

}  // namespace chain
