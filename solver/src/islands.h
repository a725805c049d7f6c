// SPDX-License-Identifier: MIT
// Resting islands left out of a step (WorldDef::skip_rest), to the bit.
//
// rest.h skips a step when the whole world is its own fixed point. Most worlds have a part at
// rest and a part that moves. An island here is a set of movable bodies that came within a touch
// (kMargin) of no other movable body during a step: the boxes around every place each held
// (reach.h) grown by that margin meet only each other's. What the modern step does to an island
// depends on its bodies, the static bodies, dt, and nothing else of the world, once:
//   - the step is not cut by the budget (a step whose budget the island's own last spend would
//     take beyond what is left is solved whole instead),
//   - the step asks no renumbering of the layout (those steps are solved whole: Layout::due_next),
//   - no squeeze is remembered by or crush reported for its bodies,
//   - continuous collision counts the move the island would make (integrated_move);
// the order of contacts, passes, walls and chains keeps each island's relative order whatever
// the others hold (chain_resolver.h, force_static.h). So an island whose bodies began a step at
// velocity +0 and came out of it where they began, at velocity +0 (in bits), alone, begins the
// next step of the same dt from the state it began this one from, and would come out the same:
// it is left out, integration included, until something comes near it or the API changes one
// of its bodies. Before such a step, every body to be solved that could reach a left-out island
// on its way (its integrated move, grown) wakes that island; after it, a solved body that came
// within the margin of a left-out one, moved one, or a cut step, means the guess was wrong: the
// step is undone and solved whole (StepStats::redone), which gives the same bits as ever.
// Islands are left out only where that pays: where what all of them together would resolve
// outweighs the checks (settle()); which ones are left out never changes a result.
#pragma once

#include "bodies.h"
#include "broadphase.h"
#include "chain_resolver.h"
#include "motion.h"
#include "reach.h"
#include "step_context.h"

#include <chain/types.h>

#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

namespace chain::detail {

class Islands {
 public:
  // The slots changed (canonicalize, renumber): every body is solved from the next step on.
  void reset(std::uint32_t slots);
  // Body `s` changed through the API, leaves its slot, or its slot took a created body: its
  // island is solved from the next step on, and `s` must come to rest again to join one.
  void wake(std::uint32_t s);

  // Before a step of dt: leaves out the resting islands no body to be solved may reach, unless
  // `whole` (a step the layout may renumber after solves every body). True when it leaves some
  // out; then runs(), skipped() and skipped_spend() describe the step, and save() must be called
  // before it moves a body.
  bool plan(const Bodies& b, const Broadphase& bp, Vec2 gravity, double dt, double tolerance,
            bool whole);
  std::span<const SlotRun> runs() const { return {runs_.data(), run_count_}; }
  const std::uint8_t* skipped() const { return skipped_.data(); }
  std::uint64_t skipped_spend() const { return skipped_spend_; }
  std::uint32_t skipped_bodies() const { return skipped_count_; }
  void save(const Bodies& b);
  // The step that plan() shaped met a left-out island: every body goes back to where the step
  // began (the solved ones to their saved velocities) and none is left out.
  void undo(Bodies& b);

  // Whether this step keeps where bodies went (a world with too little at rest, or whose islands
  // did not pay, does not look, and looks again after 1, 3, 7 ... up to 31 steps, as rest.h
  // does).
  bool tracking() const { return tracking_; }
  // After integration, when tracking(): every solved body's reach starts at its start and
  // integrated centre.
  Reach* begin_reach(const Bodies& b);
  std::uint32_t* spent() { return tracking_ ? spent_.data() : nullptr; }
  // Off, no island is woken ahead of a body that may reach it: every meeting is found after its
  // step, which is solved again (for tests of that path).
  void guess(bool on) { guess_ = on; }
  // Off, islands are left out even where what they would resolve does not pay for the checks
  // (settle()): for tests, which must leave islands out to prove anything.
  void weigh(bool on) { weigh_ = on; }

  // After a step that left islands out, before settle(): adds the left-out bodies' pushes of
  // their last solve to the static bodies' touching flags, as solving them would have.
  void touch_statics(Bodies& b);

  // After a solved step. False when the step left islands out and some solved body came near
  // one, moved one, or the step was cut: undo() and solve it whole. Otherwise files which bodies
  // came to rest and the islands that may be left out from the next step on. `fast`: the
  // bodies fast this step; `crushed`: the bodies crushes were reported for.
  bool settle(const Bodies& b, const Broadphase& bp, const ChainResolver& resolver,
              std::span<const std::uint32_t> fast, std::span<const CrushRecord> crushed, bool cut,
              Vec2 gravity, double dt, double tolerance);

 private:
  // A touch, for every rule of the step that reads another body (overlap beyond the touch
  // tolerance, flush faces, support): boxes farther apart than this never met. In metres, to
  // which settle() adds twice the touch tolerance.
  static constexpr double kMargin = 1.0e-4;
  static constexpr std::uint32_t kMaxWait = 31;
  // settle(): a body that went farther than this many refile distances queries its neighbours.
  static constexpr double kFarShare = 4.0;
  static constexpr std::uint8_t kRested = 2;  // still() of a body two solved steps at rest

  template <class Fn>
  void each_solved(const Bodies& b, Fn&& fn) const;
  void wake_island(std::uint32_t s);
  std::uint32_t find(std::uint32_t i);
  // A box: centre and half extents.
  struct Box {
    double x, y, hx, hy;
  };
  // Where a body may have been this step (solved) or would be (left out): its box around its
  // start, grown by how far it went (reach.h) or went when last solved.
  Box held_box(const Bodies& b, std::uint32_t i) const {
    return {b.start[i].x, b.start[i].y, b.hx(i) + far_[i], b.hy(i) + far_[i]};
  }
  // Whether two boxes come within `gap` of each other on both axes.
  static bool near(const Box& p, const Box& q, double gap) {
    return std::abs(p.x - q.x) - (p.hx + q.hx) <= gap && std::abs(p.y - q.y) - (p.hy + q.hy) <= gap;
  }
  // Whether leaving out bodies that took `spend` of the budget when last solved pays for the
  // checks of the `solved` bodies left in (settle()): the one rule, before a search and after.
  static bool pays(std::uint64_t spend, std::uint64_t solved) { return 2 * spend >= solved; }
  // How far a body at rest may go in a step and still be one (settle()).
  static double cap_of(const Broadphase& bp) { return bp.refile_distance(); }
  // Per slot: flags_ bits.
  static constexpr std::uint8_t kStillMask = 3;  // solved steps in a row it came out at rest, <= 2
  static constexpr std::uint8_t kRests = 4;      // settle(): came out of this step at rest
  static constexpr std::uint8_t kOpen = 8;       // settle(): came near a body not at rest (roots:
                                                 // its island did)
  static constexpr std::uint8_t kRoot = 16;      // settle(): its island's union-find root
  std::uint8_t still(std::uint32_t i) const { return flags_[i] & kStillMask; }

  std::vector<double> far_;            // per slot: reach of the step (reach.h)
  std::vector<std::uint8_t> skipped_;  // per slot: left out of this step; after settle(), the next
  std::vector<std::uint8_t> flags_;    // per slot
  // Per slot: the next body of its island, around (itself: in none). During settle() the solved
  // bodies, in none, use it as their union-find parent.
  std::vector<std::uint32_t> next_;
  std::vector<std::uint32_t> spent_;   // per slot: budget its chains took when last solved
  std::vector<Point> saved_v_;         // the solved bodies' velocities before the step, run order
  std::vector<SlotRun> runs_;          // the first run_count_ hold this step's runs
  std::vector<std::uint32_t> solved_;  // the first solved_count_: the slots of the runs, one by one
  std::uint32_t run_count_ = 0, solved_count_ = 0;
  std::span<const std::uint32_t> solved() const { return {solved_.data(), solved_count_}; }
  std::vector<std::uint32_t> changed_;  // bodies wake() saw since the last plan()
  std::vector<std::uint32_t> to_wake_;  // settle(): left-out bodies a moving one may reach next
  Reach reach_;
  std::vector<StaticTouch> touches_;  // this step's pushes against static bodies
  std::vector<StaticTouch> kept_;     // the left-out bodies' (and some woken since)
  bool woke_ = false;                 // some island woke since kept_ was last pruned
  std::uint64_t skipped_spend_ = 0;   // spent_ summed over the left-out bodies
  std::uint32_t skipped_count_ = 0;
  double dt_ = 0.0;       // the dt the left-out islands rested at
  bool planned_ = false;  // this step leaves some out
  bool guess_ = true;
  bool weigh_ = true;
  bool tracking_ = true;
  bool counted_last_ = false;  // the last step counted the still steps
  std::uint32_t backoff_ = 0, wait_ = 0;
  std::uint32_t unpaid_ = 0;  // settle(): the wait the last island search that did not pay set
};

}  // namespace chain::detail
