// SPDX-License-Identifier: MIT
// The inelastic velocity rule.
//
// Every push between two bodies is recorded as a link along its axis. After the pushes of a
// step, the dynamic bodies linked along an axis (only links whose bodies were closing or at rest
// relative to each other) form a group that leaves with one velocity on that axis: the
// mass-weighted mean, which conserves momentum as a perfectly inelastic collision does, or, when
// the group was pushed against immovable bodies, their velocity. With restitution, each body
// instead reverses its velocity relative to the group's, scaled by the group's restitution.
#pragma once

#include "bodies.h"
#include "buffer.h"
#include "worker_pool.h"

#include <cstdint>
#include <vector>

namespace chain::detail {

class VelocityResponse {
 public:
  void clear() {
    links_.clear();
    per_axis_[0] = per_axis_[1] = 0;
  }
  // Sizes the link list for a body set of n, as the resolver sizes its contact lists: a step then
  // records two pushes a body without allocating (a check for room of one's own in add() cost
  // the walls' loop, which records every push, 4% of a resting pyramid's step).
  void reserve(std::size_t n) { reserve_buffer(links_, 2 * n); }
  // `a` was pushed out of `b` along axis (0 = x, 1 = y) in direction sign.
  void add(std::uint32_t a, std::uint32_t b, int axis, double sign) {
    links_.push_back(
        {a, b, static_cast<std::uint8_t>(axis), sign > 0.0 ? std::int8_t{1} : std::int8_t{-1}});
    ++per_axis_[axis];
  }
  // The axes are independent (each reads and writes its own velocity component): with workers,
  // they run at once, each in buffers of its own.
  void apply(Bodies& bodies, double restitution_threshold, WorkerPool& pool);

  struct Link {  // a was pushed out of b along axis, in direction sign
    std::uint32_t a, b;
    std::uint8_t axis;
    std::int8_t sign;
  };
  // The pushes of the step so far, in the order they happened.
  const std::vector<Link>& links() const { return links_; }

 private:
  // Per dynamic slot: the groups of one axis (parent_ kNoSlot: in none).
  struct Groups {
    std::vector<std::uint32_t> parent_, root_;
    std::vector<double> mass_, momentum_, anchor_sum_, restitution_, spread_;
    std::vector<std::uint32_t> anchor_count_;
    std::vector<const Link*> anchored_;  // this pass's closing links to immovable bodies
  };
  void apply_axis(Bodies& bodies, int axis, double restitution_threshold, Groups& g) const {
    if (bodies.bounces) {
      apply_axis<true>(bodies, axis, restitution_threshold, g);
    } else {
      apply_axis<false>(bodies, axis, restitution_threshold, g);
    }
  }
  // kBounces false: no body has a restitution above 0 (Bodies::bounces), and the groups'
  // restitutions, all 0, are not summed.
  template <bool kBounces>
  void apply_axis(Bodies& bodies, int axis, double restitution_threshold, Groups& g) const;

  std::vector<Link> links_;
  // Links per axis: a world at rest pushes along one, and the other needs no pass over the links.
  std::size_t per_axis_[2] = {0, 0};
  Groups groups_[2];  // one for both axes in turn, or one each when they run at once
};

}  // namespace chain::detail
