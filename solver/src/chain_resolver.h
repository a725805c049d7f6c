// SPDX-License-Identifier: MIT
// The modern collision-chaining resolver.
//
// Fast bodies are swept first (continuous.h). Then a contact pass finds every overlapping pair and
// resolves them in shock-propagation order: contacts with immovable bodies first (each body's in
// the order it entered them), then outward by contact-graph distance from them. Resolving a pair
// starts a chain:
//   - against an immovable body, the dynamic body is pushed out through the face it came in
//     through (entry_face.h), takes the whole push and acts as a wall from then on
//     (force_static.h); against a body supported from that side, the same along least overlap;
//   - between two dynamic bodies, the push is split by mass, where the mass of a side includes
//     every body already moving with it (the additional mass), and each pushed body carries the
//     chain on to the bodies it now overlaps: first a's side (pushed back), then b's (pushed on).
//     A body pushed back by its own chain brings the bodies behind it along (follow-back). If
//     a's side ends up backed by an immovable body, b's side continues force-static.
// Chained pushes stay on the axis of the push that caused them (the chaining axis), so a resting
// contact is never resolved sideways. Each body joins a chain at most once, and a step has a
// fixed budget of pair resolutions, so work is bounded. Passes repeat, up to
// WorldDef::max_passes, only while a chain left overlaps behind.
//
// Chains between dynamic bodies run on an explicit stack: a row of 10,000 boxes chains 10,000
// deep.
#pragma once

#include "box_overlap.h"
#include "chain_state.h"
#include "continuous.h"
#include "force_static.h"
#include "slot_list.h"
#include "step_context.h"

#include <cstdint>
#include <span>
#include <vector>

namespace chain::detail {

class ChainResolver {
 public:
  void resolve(StepContext& ctx);
  // The last step's dynamic bodies in the order it first reached them, and the number of jumps
  // in memory on the way (see ChainState::reach_order).
  std::span<const std::uint32_t> reach_order() const { return state_.reach_order(); }
  std::size_t reach_jumps() const { return state_.reach_jumps(); }
  // The slots were renumbered: forgets every per-body mark and the near pairs.
  void forget_slots();
  // Scans the near pairs anew, grid rebuilt, at the start of every step's first pass, as a fresh
  // broadphase would: for tests that no result depends on when they were scanned.
  void rescan_every_step(bool on) { rescan_every_step_ = on; }
  // Steps that scanned the near pairs, and steps that took them from an earlier scan while some
  // body was filed again since (those whose contacts and overlaps merge the refiled ones in).
  std::uint64_t scans() const { return scans_; }
  std::uint64_t reuses_with_refiled() const { return reuses_with_refiled_; }
  // The near lists of the last scan, while they serve the broadphase as it is (its generation):
  // every body a body not filed again since could have come within 2 refile distances of is in
  // its list (entries: ChainState::entry_slot).
  bool near_lists_serve(const Broadphase& bp) const { return near_generation_ == bp.generation(); }
  std::span<const std::uint32_t> near(std::uint32_t body) const { return state_.near(body); }
  // The last pass's contacts, in the order it found them (before order_contacts): for tests.
  std::span<const Pair> contacts() const { return contacts_; }
  // The next step reads a squeeze this one or the last remembered (ForceStatic::kept_squeeze):
  // besides the bodies, the only state a step hands the next.
  bool remembers_squeezes() const { return walls_.remembers_squeezes(); }
  bool squeezed_lately(std::uint32_t body) const { return walls_.squeezed_lately(body); }
  // Around a step that may be solved again (ForceStatic::mark): what it squeezed is undone, or
  // kept.
  void mark() { walls_.mark(); }
  void undo() { walls_.undo(); }
  void keep() { walls_.keep(); }

 private:
  enum class Stage : std::uint8_t { kBack, kForward };
  struct Frame {
    std::uint32_t a, b;    // a is pushed out of b
    std::uint32_t anchor;  // immovable body backing this chain, for crush reports
    std::uint32_t cand_begin, cand_end, cursor;
    double extra;            // mass moving with a besides a itself
    double moved;            // a's displacement along chain_axis, follow-backs included
    std::int8_t axis;        // axis this frame may push along, or kAnyAxis
    std::int8_t chain_axis;  // axis of this frame's push
    std::int8_t sign;        // direction a was pushed along chain_axis
    std::int8_t backing;     // direction in which a is backed by an immovable body, 0 if none
    Stage stage;
    bool frozen;  // a's side is backed away from b: b's side continues force-static
  };

  void gather_contacts(StepContext& ctx);
  // The contacts of stale body i (filed again since the near pairs were taken) into `out`: each
  // with a body before it or not stale, as its lower body, then its higher.
  void add_refiled_pairs(const StepContext& ctx, std::uint32_t i, std::vector<Pair>& out) const;
  void gather_suspect_contacts(StepContext& ctx);
  void order_contacts(StepContext& ctx);
  // Orders each body's contacts with immovable bodies (among the first `count` of ordered_) by
  // when the body entered each, at the place of its first.
  void order_entries(StepContext& ctx, std::size_t count);
  void run_chain(StepContext& ctx, std::uint32_t a, std::uint32_t b);
  // Resolves (a, b): returns true when the push was split and the frame must go on to chain;
  // a force-static push queues its walls, which the caller runs.
  // `follower` follows a back when this frame hands back (the other body of the frame below): a's
  // own moves are not stopped by it.
  bool open(StepContext& ctx, std::uint32_t a, std::uint32_t b, double extra, int axis,
            bool force_static, std::uint32_t anchor, std::uint32_t follower = kNoSlot);
  void gather_candidates(StepContext& ctx, Frame& f, std::uint32_t around);
  // Next candidate of f that body `from` now overlaps and that may still join the chain.
  // Inlined into the chain loop: called twice a body, its call cost a fifth of the walk.
  [[gnu::always_inline]] inline bool next_candidate(StepContext& ctx, Frame& f, std::uint32_t from,
                                                    std::uint32_t& c);
  void close(StepContext& ctx);
  // What a finished frame hands the one below it: how far its a moved along the chaining axis
  // (follow-backs included), and the immovable body backing it, from which side (0: none).
  struct Result {
    double moved;
    std::uint32_t anchor;
    std::int8_t backing;
  };
  // Hands the result of a frame that just finished to the frame below it on the stack.
  void hand_back(StepContext& ctx, const Result& done);

  ChainState state_;
  ForceStatic walls_;
  ContinuousCollision continuous_;
  // Continuous collision built the broadphase this step, and its near pairs are not scanned yet.
  bool fresh_grid_ = false;
  bool rescan_every_step_ = false;
  std::uint64_t scans_ = 0, reuses_with_refiled_ = 0;
  bool repeat_immovable_ = false;  // some body has several immovable contacts in this pass
  struct Entry {
    Pair pair;
    double when;
    std::uint32_t first;  // where the body's first immovable contact is in the order
  };
  std::vector<Entry> entries_;
  std::vector<std::uint32_t> first_entry_;  // per body of involved_
  std::vector<Pair> contacts_, ordered_, near_pairs_;
  // Contact ordering, over the bodies the contacts touch (numbered through local_).
  std::vector<std::uint32_t> involved_, local_, local_mark_;
  std::uint32_t mark_ = 0;
  std::vector<std::uint32_t> level_, adj_start_, adj_, queue_, level_count_;
  std::vector<Frame> stack_;
  SlotList cands_;         // the open frames' candidates, end to end
  OverlapTest test_{0.0};  // the step's overlap test, made once for every walk of its chains
  std::vector<std::uint32_t> found_;  // one suspect body's overlaps
  // With workers: contacts found per block of kBlock bodies, each block's from the start of its
  // bodies' near lists on (in near_pairs_).
  static constexpr std::uint32_t kBlock = 2048;
  std::vector<std::uint32_t> block_found_;
  // The near pairs are scanned again once more than one body in this many was filed again since.
  static constexpr std::uint32_t kRescanShare = 8;
  Result last_{};  // the result of the last open() that did not open a frame
  // Broadphase generation the near pairs were scanned in, or kNotScanned (no generation has it:
  // a world that steps before its first body has generation 0, and no near lists).
  static constexpr std::uint64_t kNotScanned = ~std::uint64_t{0};
  std::uint64_t near_generation_ = kNotScanned;
  // The broadphase's examined() when the near pairs were last scanned, and what the scan and its
  // build examined (bodies filed count one each).
  std::uint64_t examined_after_scan_ = 0, scan_cost_ = 0;
};

}  // namespace chain::detail
