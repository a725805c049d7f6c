// The modern collision-chaining resolver.
//
// A sweep finds every overlapping pair and resolves them in shock-propagation order: contacts
// with immovable bodies first, then outward by contact-graph distance from them. Resolving a
// pair starts a chain:
//   - against an immovable body (or one acting as immovable, "force-static"), the dynamic body
//     takes the whole push and then acts as a wall for the dynamic bodies it now overlaps;
//   - between two dynamic bodies, the push is split by mass, where the mass of a side includes
//     every body already moving with it (the additional mass), and each pushed body carries the
//     chain on to the bodies it now overlaps. A body pushed back by its own chain brings the
//     bodies behind it along (follow-back).
// Chained pushes stay on the axis of the push that caused them (the chaining axis), so a resting
// contact is never resolved sideways. A body placed against an immovable one is *supported* for
// the rest of the sweep: pushed towards its support, it acts as a wall, and a wall that meets it
// yields instead (shock propagation: each level treats the level below as immovable). Each body
// joins a chain at most once (visited marks), and a step has a fixed budget of pair resolutions, so
// work is bounded. A dynamic body pushed by an immovable chain into another immovable body is
// crushed: it is centred between the two, reported, and left alone for the rest of the step. Sweeps
// repeat, up to WorldDef::max_passes, only while a chain left overlaps behind (a follow-back, a
// masked axis, a revisit, a crush).
//
// Chains run on an explicit stack: a row of 10,000 boxes chains 10,000 deep.
#pragma once

#include "step_context.h"

#include <cstdint>
#include <vector>

namespace chain::detail {

class ChainResolver {
 public:
  void resolve(StepContext& ctx);

 private:
  struct Contact {
    std::uint32_t a, b;
  };
  enum class Stage : std::uint8_t { kEnter, kWall, kBack, kForward };
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
    bool force_static;  // b acts as immovable
    bool frozen;        // a is backed away from b: b's own chain runs force-static
  };

  void gather_contacts(StepContext& ctx);
  void order_contacts(StepContext& ctx);
  void run_chain(StepContext& ctx, std::uint32_t a, std::uint32_t b);
  void push_frame(StepContext& ctx, std::uint32_t a, std::uint32_t b, double extra, int axis,
                  bool force_static, std::uint32_t anchor);
  bool enter(StepContext& ctx, Frame& f);
  void gather_candidates(StepContext& ctx, Frame& f, std::uint32_t around);
  // Next candidate of f that body `from` now overlaps and that may still join the chain.
  bool next_candidate(StepContext& ctx, Frame& f, std::uint32_t from, std::uint32_t& c);
  // Direction in which c is pushed out of `from` along axis (+1 or -1).
  static int away(const StepContext& ctx, int axis, std::uint32_t from, std::uint32_t c);
  bool supported_towards(int axis, std::uint32_t body, int direction) const {
    return support_[axis][body] == direction;
  }
  void support(int axis, std::uint32_t body, int direction, std::uint32_t anchor);
  // The wall f.a meets a body supported where the wall would push it: the wall moves instead.
  void yield_to(StepContext& ctx, Frame& f, std::uint32_t c);
  void crush_check(StepContext& ctx, Frame& f, std::uint32_t body, std::uint32_t wall, int side);
  void report_crush(StepContext& ctx, std::uint32_t body, std::uint32_t anchor,
                    std::uint32_t blocker, int axis);
  void finish(StepContext& ctx);

  std::vector<Contact> contacts_, ordered_;
  std::vector<std::uint32_t> level_, adj_start_, adj_, queue_, level_count_;
  std::vector<std::uint32_t> visited_;   // chain stamp of the last chain a body joined
  std::vector<std::uint32_t> on_stack_;  // frames on the stack that hold a body as a or b
  std::vector<std::uint8_t> crushed_;
  std::vector<std::int8_t> support_[2];        // per axis: direction a body is backed in, or 0
  std::vector<std::uint32_t> support_anchor_;  // the immovable body behind that support
  std::vector<Frame> stack_;
  std::vector<std::uint32_t> cands_;
  std::uint32_t stamp_ = 0;
  bool leftover_ = false;
  bool cut_ = false;
};

}  // namespace chain::detail
