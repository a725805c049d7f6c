#include "velocity_response.h"

#include <algorithm>
#include <cmath>

namespace chain::detail {

std::uint32_t VelocityResponse::Groups::find(std::uint32_t i) {
  while (parent_[i] != i) {
    parent_[i] = parent_[parent_[i]];  // path halving
    i = parent_[i];
  }
  return i;
}

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

void VelocityResponse::apply_axis(Bodies& bodies, int axis, double restitution_threshold,
                                  Groups& g) const {
  auto& [parent_, root_, member_, mass_, momentum_, anchor_sum_, restitution_, spread_,
         anchor_count_] = g;
  auto find = [&g](std::uint32_t i) { return g.find(i); };
  if (per_axis_[axis] == 0) return;
  const std::uint32_t n = bodies.dynamic_end;
  double* v = axis == 0 ? bodies.vx.data() : bodies.vy.data();
  parent_.resize(n);
  root_.resize(n);
  member_.assign(n, 0);
  for (auto* a : {&mass_, &momentum_, &anchor_sum_, &restitution_, &spread_})
    a->resize(n);
  anchor_count_.resize(n);

  // A link joins two bodies only while they close in or rest on each other: a pair that an
  // earlier push already set apart keeps its velocities.
  auto closing = [&](const Link& l) {
    return (v[l.a] - v[l.b]) * static_cast<double>(l.sign) <= 0.0;
  };
  bool any = false;
  for (std::uint32_t i = 0; i < n; ++i)
    parent_[i] = i;
  for (const Link& l : links_) {
    if (l.axis != axis || !closing(l)) continue;
    any = true;
    member_[l.a] = 1;
    if (bodies.immovable(l.b)) continue;
    member_[l.b] = 1;
    const std::uint32_t ra = find(l.a), rb = find(l.b);
    // The smaller slot becomes the root, so groups do not depend on link order.
    if (ra != rb) parent_[std::max(ra, rb)] = std::min(ra, rb);
  }
  if (!any) return;

  // Sums run in slot order: the same bits for any creation order. A group's root is its smallest
  // slot, so it comes first, and its sums are cleared before any member adds to them.
  double max_restitution = 0.0;
  for (std::uint32_t i = 0; i < n; ++i) {
    if (!member_[i]) continue;
    const std::uint32_t r = root_[i] = find(i);
    if (r == i) {
      mass_[r] = momentum_[r] = anchor_sum_[r] = restitution_[r] = spread_[r] = 0.0;
      anchor_count_[r] = 0;
    }
    mass_[r] += bodies.mass[i];
    momentum_[r] += bodies.mass[i] * v[i];
    restitution_[r] = std::max(restitution_[r], bodies.restitution[i]);
    max_restitution = std::max(max_restitution, bodies.restitution[i]);
  }
  for (const Link& l : links_) {
    if (l.axis != axis || !bodies.immovable(l.b) || !closing(l)) continue;
    const std::uint32_t r = root_[l.a];
    anchor_sum_[r] += v[l.b];
    ++anchor_count_[r];
    restitution_[r] = std::max(restitution_[r], bodies.restitution[l.b]);
    max_restitution = std::max(max_restitution, bodies.restitution[l.b]);
  }
  // momentum_ becomes the group velocity: the anchors' mean (several only when a body is
  // crushed between them) or the mass-weighted mean.
  auto group_velocity = [&](std::uint32_t r) {
    momentum_[r] = anchor_count_[r] > 0 ? anchor_sum_[r] / static_cast<double>(anchor_count_[r])
                                        : momentum_[r] / mass_[r];
  };
  if (max_restitution == 0.0) {
    // No group bounces: every member takes its group's velocity, in the same pass, as a group's
    // root (its smallest slot) comes before its other members.
    for (std::uint32_t i = 0; i < n; ++i) {
      if (!member_[i]) continue;
      if (root_[i] == i) group_velocity(i);
      v[i] = momentum_[root_[i]];
    }
    return;
  }
  for (std::uint32_t i = 0; i < n; ++i) {
    if (member_[i] && root_[i] == i) group_velocity(i);
  }
  for (std::uint32_t i = 0; i < n; ++i) {
    if (member_[i])
      spread_[root_[i]] = std::max(spread_[root_[i]], std::abs(v[i] - momentum_[root_[i]]));
  }
  for (std::uint32_t i = 0; i < n; ++i) {
    if (!member_[i]) continue;
    const std::uint32_t r = root_[i];
    const double group_v = momentum_[r];
    const double e = restitution_[r];
    v[i] =
        (e > 0.0 && spread_[r] >= restitution_threshold) ? group_v - e * (v[i] - group_v) : group_v;
  }
}

}  // namespace chain::detail
