// SPDX-License-Identifier: MIT
#include "velocity_response.h"

#include "buffer.h"

#include <algorithm>
#include <cmath>

namespace chain::detail {

void VelocityResponse::apply(Bodies& bodies, double restitution_threshold, WorkerPool& pool) {
  if (links_.empty()) return;
  // A world at rest pushes along one axis only: the workers would wake for nothing.
  const bool both = per_axis_[0] > 0 && per_axis_[1] > 0;
  if (pool.threads() == 1 || !both) {
    apply_axis(bodies, 0, restitution_threshold, groups_[0]);
    apply_axis(bodies, 1, restitution_threshold, groups_[0]);
    return;
  }
  pool.run(2, [&](std::uint32_t axis) {
    apply_axis(bodies, static_cast<int>(axis), restitution_threshold, groups_[axis]);
  });
}

template <bool kBounces>
void VelocityResponse::apply_axis(Bodies& bodies, int axis, double restitution_threshold,
                                  Groups& g) const {
  if (per_axis_[axis] == 0) return;
  const std::uint32_t n = bodies.dynamic_end;
  for (auto* a : {&g.parent_, &g.root_, &g.anchor_count_})
    resize_buffer(*a, n);
  for (auto* a : {&g.mass_, &g.momentum_, &g.anchor_sum_, &g.restitution_, &g.spread_})
    resize_buffer(*a, n);
  // Through local pointers: the loops below store into several of these arrays, and through the
  // vectors every store would have the others' data pointers reloaded.
  double* const v = axis == 0 ? bodies.vx.data() : bodies.vy.data();
  const double* const body_mass = bodies.mass.data();
  const double* const body_restitution = bodies.restitution.data();
  std::uint32_t* const parent = g.parent_.data();
  std::uint32_t* const root = g.root_.data();
  std::uint32_t* const anchor_count = g.anchor_count_.data();
  double* const mass = g.mass_.data();
  double* const momentum = g.momentum_.data();
  double* const anchor_sum = g.anchor_sum_.data();
  double* const restitution = g.restitution_.data();
  double* const spread = g.spread_.data();
  auto find = [parent](std::uint32_t i) {
    for (std::uint32_t up = parent[i]; up != i; up = parent[i]) {
      const std::uint32_t above = parent[up];
      // up is the root: halving would write parent[i] = up again (at rest, nearly every find).
      if (above == up) return up;
      parent[i] = above;  // path halving
      i = above;
    }
    return i;
  };

  // A link joins two bodies only while they close in or rest on each other: a pair that an
  // earlier push already set apart keeps its velocities.
  auto closing = [&](const Link& l) {
    return (v[l.a] - v[l.b]) * static_cast<double>(l.sign) <= 0.0;
  };
  // kNoSlot: in no group. A body joins as a group of its own when a link first names it.
  std::fill_n(parent, n, kNoSlot);
  // The closing links to immovable bodies, in link order, for the anchors' pass: allocates only
  // when links_ itself did.
  std::vector<const Link*>& anchored = g.anchored_;
  if (anchored.capacity() < links_.capacity()) anchored.reserve(links_.capacity());
  anchored.clear();
  bool any = false;
  // Each link copied: stores into parent[] (32-bit, as the links' slots are) could otherwise
  // change it, and its slots were loaded again after each.
  for (const Link& link : links_) {
    const Link l = link;
    if (l.axis != axis || !closing(l)) continue;
    any = true;
    // A body a link names for the first time is its own root: find() is skipped for it.
    const bool fresh_a = parent[l.a] == kNoSlot;
    if (fresh_a) parent[l.a] = l.a;
    if (l.b >= n) {  // immovable
      anchored.push_back(&link);
      continue;
    }
    const bool fresh_b = parent[l.b] == kNoSlot;
    if (fresh_b) parent[l.b] = l.b;
    const std::uint32_t ra = fresh_a ? l.a : find(l.a), rb = fresh_b ? l.b : find(l.b);
    // The smaller slot becomes the root, so groups do not depend on link order.
    if (ra != rb) parent[std::max(ra, rb)] = std::min(ra, rb);
  }
  if (!any) return;

  // A group held by immovable bodies takes their mean velocity, summed in link order; found
  // before the slot-order pass, which then sums masses and momenta only for the groups that use
  // them (at rest, nearly none: every group stands on something). A held root is marked kHeld in
  // root[], which holds slots otherwise and which the slot-order pass then writes for every
  // member of every group, so no mark lasts; the other roots' counts are cleared there (a fill of
  // every body's count cost more than both).
  constexpr std::uint32_t kHeld = kNoSlot;
  for (const Link* const anchor : anchored) {
    const Link& l = *anchor;
    const std::uint32_t r = find(l.a);
    if (root[r] != kHeld) {
      root[r] = kHeld;
      anchor_sum[r] = 0.0;
      anchor_count[r] = 0;
    }
    anchor_sum[r] += v[l.b];
    ++anchor_count[r];
  }
  // momentum becomes the group velocity: the anchors' mean (several only when a body is
  // crushed between them) or the mass-weighted mean.
  auto group_velocity = [&](std::uint32_t r) {
    momentum[r] = anchor_count[r] > 0 ? anchor_sum[r] / static_cast<double>(anchor_count[r])
                                      : momentum[r] / mass[r];
  };
  // Sums run in slot order: the same bits for any creation order. A group's root is its smallest
  // slot, so it comes first, and its sums are cleared before any member adds to them.
  double max_restitution = 0.0;
  bool free_groups = false;  // some group no immovable body holds
  for (std::uint32_t i = 0; i < n; ++i) {
    if (parent[i] == kNoSlot) continue;
    // A parent is a member of a smaller slot (unions hang the larger root under the smaller), so
    // its root is known by now: find(i) without walking the path.
    std::uint32_t r = i;
    if (parent[i] == i) {
      if (root[i] != kHeld) anchor_count[i] = 0;
    } else {
      r = root[parent[i]];
    }
    root[i] = r;
    if constexpr (kBounces) {
      if (r == i) restitution[r] = spread[r] = 0.0;
      restitution[r] = std::max(restitution[r], body_restitution[i]);
      max_restitution = std::max(max_restitution, body_restitution[i]);
    }
    if (anchor_count[r] > 0) {
      // Without kBounces, a held group's velocity is known already: its members take it here
      // (the root first), and the pass below, the same again, is left for the other groups.
      if constexpr (!kBounces) {
        if (r == i) group_velocity(r);
        v[i] = momentum[r];
      }
      continue;
    }
    free_groups = true;
    if (r == i) mass[r] = momentum[r] = 0.0;
    mass[r] += body_mass[i];
    momentum[r] += body_mass[i] * v[i];
  }
  if constexpr (kBounces) {
    for (const Link* const anchor : anchored) {
      const Link& l = *anchor;
      const std::uint32_t r = root[l.a];
      restitution[r] = std::max(restitution[r], body_restitution[l.b]);
      max_restitution = std::max(max_restitution, body_restitution[l.b]);
    }
  }
  // Without kBounces, max_restitution stays 0: std::max(0, r) is 0 for every r that is not
  // above 0.
  if (max_restitution == 0.0) {
    if (!kBounces && !free_groups) return;  // every member has its velocity
    // No group bounces: every member takes its group's velocity, in the same pass, as a group's
    // root (its smallest slot) comes before its other members.
    for (std::uint32_t i = 0; i < n; ++i) {
      if (parent[i] == kNoSlot) continue;
      if (root[i] == i) group_velocity(i);
      v[i] = momentum[root[i]];
    }
    return;
  }
  for (std::uint32_t i = 0; i < n; ++i) {
    if (parent[i] != kNoSlot && root[i] == i) group_velocity(i);
  }
  for (std::uint32_t i = 0; i < n; ++i) {
    if (parent[i] != kNoSlot)
      spread[root[i]] = std::max(spread[root[i]], std::abs(v[i] - momentum[root[i]]));
  }
  for (std::uint32_t i = 0; i < n; ++i) {
    if (parent[i] == kNoSlot) continue;
    const std::uint32_t r = root[i];
    const double group_v = momentum[r];
    const double e = restitution[r];
    v[i] =
        (e > 0.0 && spread[r] >= restitution_threshold) ? group_v - e * (v[i] - group_v) : group_v;
  }
}

template void VelocityResponse::apply_axis<true>(Bodies&, int, double, Groups&) const;
template void VelocityResponse::apply_axis<false>(Bodies&, int, double, Groups&) const;

}  // namespace chain::detail
