// SPDX-License-Identifier: MIT
// MetricsRecorder::observe: the per-step half of the metrics, at a cost that follows what moved.
//
// Every figure of a step depends on the positions, angles and velocities of the bodies in it and
// on pairs of bodies whose boxes touch. A pair of bodies that did not move in the step overlaps as
// it did after the step before, passes through nothing, and (until the last step, where the
// tolerances change) cannot become the worst overlap, which it already was or was not. So a step
// re-judges only the pairs with a moved body, which a PairCache lists from each moved body's
// candidates. The pairs that overlapped are kept from step to step, so that the step's deepest
// overlap and each body's deepest are taken over all of them. When more than half of the bodies
// moved, judging every pair the cache lists is cheaper, and is done instead.
//
// Where several pairs tie (the same depth, or the same ratio to their tolerance in one step) the
// lowest pair is named, so that the figures do not depend on the order pairs are met in.
#include "judge/metrics.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <iterator>

namespace chainbench {
namespace {

// The part of body i's move in a step that its velocity does not explain, metres; rounding of its
// position (two units in the last place) counts as 0, so a body at rest reads 0, not 1e-16.
double energy_free_displacement(const BodyState& before, const BodyState& after, std::size_t i,
                                double dt) {
  const double dx = after.position[i].x - before.position[i].x - dt * after.velocity[i].x;
  const double dy = after.position[i].y - before.position[i].y - dt * after.velocity[i].y;
  if (dx == 0.0 && dy == 0.0) return 0.0;
  const double d = std::sqrt(dx * dx + dy * dy);  // positions stay far below overflow
  return below_resolution(d, magnitude(after.position[i])) ? 0.0 : d;
}

// One unit in the last place of a single-precision coordinate of this magnitude: a float engine
// far from the origin moves in steps of it.
// The next float up is the one whose bits are one more (m is finite and not negative), which
// is what std::nextafter returns, without its call.
double float_resolution(Vec2d p) {
  const auto m = static_cast<float>(std::min(magnitude(p), 3.0e38));
  const auto up = std::bit_cast<float>(std::bit_cast<std::uint32_t>(m) + 1u);
  return static_cast<double>(up - m);
}

}  // namespace

void MetricsRecorder::observe(const BodyState& before, const BodyState& after, int step,
                              bool per_body, bool depth,
                              const std::vector<std::uint32_t>* changed) {
  if (lives_) {
    presence_.at(step);
    if (sel_.stability) judge_leavers(before);
  }
  const bool displacement = sel_.displacement || per_body;
  const bool overlaps = sel_.penetration || per_body || depth || sel_.stability;
  // Reusing the last step's overlaps needs them measured on the state `before` holds, and a
  // tolerance that stays what it was: not the run's last step, where it drops to the scene's own.
  const bool follows = step == last_step_ + 1 && (!overlaps || overlaps_step_ == last_step_);
  const bool few = !every_body_ && follows && step < scene_.steps &&
                   (changed ? find_moved(before, after, *changed) : find_moved(before, after)) &&
                   (!lives_ || add_changes(after.position.size()));
  if (few) {
    if (moved_.empty()) {
      observe_still(after, step, displacement, overlaps);
    } else {
      observe_some(before, after, step, displacement, overlaps);
    }
    std::size_t kept = 0;
    for (const std::uint32_t i : moved_) {
      if (keeps_moving(i, after) && present(i)) moved_[kept++] = i;
    }
    moved_.resize(kept);
    still_.swap(moved_);
  } else {
    observe_all(before, after, step, displacement, overlaps);
    still_.clear();
    for (std::size_t i = 0; i < after.velocity.size(); ++i) {
      if (keeps_moving(i, after) && present(i)) still_.push_back(static_cast<std::uint32_t>(i));
    }
  }
  last_step_ = step;
  if (overlaps) overlaps_step_ = step;
}

bool MetricsRecorder::find_moved(const BodyState& before, const BodyState& after) {
  const std::size_t n = after.position.size(), most = n / 2;
  moved_.clear();
  // Whole blocks are compared first (values, so that a NaN always counts as a move); only a block
  // with a move in it is walked body by body.
  constexpr std::size_t kBlock = 256;
  // Angles count only where the scene turns its boxes: elsewhere no figure reads them.
  for (std::size_t start = 0; start < n; start += kBlock) {
    const std::size_t end = std::min(n, start + kBlock);
    bool any = false;
    for (std::size_t i = start; i < end; ++i)
      any |= moved(i, before, after);
    if (!any) continue;
    for (std::size_t i = start; i < end; ++i) {
      if (!moved(i, before, after)) continue;
      if (moved_.size() >= most) return false;
      moved_.push_back(static_cast<std::uint32_t>(i));
    }
  }
  return true;
}

bool MetricsRecorder::find_moved(const BodyState& before, const BodyState& after,
                                 const std::vector<std::uint32_t>& changed) {
  // A body whose state did not change moved only if it keeps moving, which it then did after the
  // last step too.
  const std::size_t most = after.position.size() / 2;
  if (changed.size() > most) return false;  // a full pass, which gives the same figures
  candidates_.clear();
  std::set_union(changed.begin(), changed.end(), still_.begin(), still_.end(),
                 std::back_inserter(candidates_));
  moved_.clear();
  for (const std::uint32_t i : candidates_) {
    if (!moved(i, before, after)) continue;
    if (moved_.size() >= most) return false;
    moved_.push_back(i);
  }
  return true;
}

bool MetricsRecorder::add_changes(std::size_t bodies) {
  const std::span<const std::uint32_t> changes = presence_.changed();
  if (changes.empty()) return true;
  candidates_.clear();
  std::set_union(moved_.begin(), moved_.end(), changes.begin(), changes.end(),
                 std::back_inserter(candidates_));
  moved_.swap(candidates_);
  return moved_.size() <= bodies / 2;
}

double MetricsRecorder::add_displacement(const BodyState& before, const BodyState& after,
                                         std::size_t i) {
  const double d = energy_free_displacement(before, after, i, dt_);
  step_efd_[i] = d;
  efd_total_ += d;
  efd_max_ = std::max(efd_max_, d);
  return d;
}

void MetricsRecorder::clear_displacements() {
  if (efd_dense_) {
    std::fill(step_efd_.begin(), step_efd_.end(), 0.0);
  } else {
    for (const std::size_t i : efd_written_)
      step_efd_[i] = 0.0;
  }
  efd_dense_ = false;
  efd_written_.clear();
}

void MetricsRecorder::observe_all(const BodyState& before, const BodyState& after, int step,
                                  bool displacement, bool overlaps) {
  if (displacement) {
    for (const std::size_t i : dynamic_) {
      if (stepped(i)) {
        add_displacement(before, after, i);
      } else {
        step_efd_[i] = 0.0;  // out of the world for the step: no displacement
      }
    }
    body_steps_ += dynamic_stepped();
    efd_dense_ = true;
    efd_written_.clear();
  }
  if (overlaps) {
    fresh_.clear();
    std::fill(step_pen_.begin(), step_pen_.end(), 0.0);
    auto judge = [&](std::size_t i, std::size_t j) { visit(before, after, i, j, step); };
    if (every_body_) {
      full_scan_->build(before, after);
      full_scan_->for_each_pair(judge);
      cache_.invalidate();
    } else {
      cache_.for_each_pair(before, after, judge);
    }
    if (sel_.stability) tunnels_.end_step();
    settle(step);
  }
  if (sel_.stability) {
    recovering_.clear();
    for (const std::size_t i : dynamic_) {
      if (!stepped(i)) continue;
      update_slack(before, after, i, step);
      if (slack_[i] < bounds_.allowance[i]) recovering_.push_back(i);
    }
  }
  if (overlaps) {
    depth_ = step_pen_;  // each body's deepest overlap now, for the next step
    overlaps_.swap(fresh_);
  }
}

void MetricsRecorder::observe_some(const BodyState& before, const BodyState& after, int step,
                                   bool displacement, bool overlaps) {
  if (displacement) {
    clear_displacements();
    // Scene order, as a full pass sums them; a body that did not move adds exactly 0.
    for (const std::uint32_t i : moved_) {
      if (scan().dynamic(i) && stepped(i) && add_displacement(before, after, i) != 0.0)
        efd_written_.push_back(i);
    }
    body_steps_ += dynamic_stepped();
  }
  if (overlaps) {
    for (const std::uint32_t i : moved_)
      active_[i] = 1;
    // Pairs at rest keep their overlap; the others are judged again below.
    fresh_.clear();
    for (const Overlap& o : overlaps_) {
      step_pen_[o.a] = step_pen_[o.b] = 0.0;
      if (!active_[o.a] && !active_[o.b]) fresh_.push_back(o);
    }
    if (sel_.stability) tunnels_.carry(after, active_);
    cache_.for_each_pair_of(before, after, moved_, active_, [&](std::size_t i, std::size_t j) {
      visit(before, after, i, j, step);
    });
    if (sel_.stability) tunnels_.end_step();
    settle(step);
  }
  if (sel_.stability) {
    // The bodies that moved and those still refilling their bucket, in scene order: a body at
    // rest with a full bucket neither sets the peak speed nor changes its bucket.
    merged_.clear();
    auto r = recovering_.begin();
    for (const std::uint32_t i : moved_) {
      if (!scan().dynamic(i)) continue;
      for (; r != recovering_.end() && *r < i; ++r)
        merged_.push_back(*r);
      if (r != recovering_.end() && *r == i) ++r;
      merged_.push_back(i);
    }
    merged_.insert(merged_.end(), r, recovering_.end());
    recovering_.clear();
    for (const std::size_t i : merged_) {
      if (!stepped(i)) continue;  // entered in the step, or left: no move, and no bucket now
      update_slack(before, after, i, step);
      if (slack_[i] < bounds_.allowance[i]) recovering_.push_back(i);
    }
  }
  if (overlaps) {
    for (const Overlap& o : overlaps_)
      depth_[o.a] = step_pen_[o.a], depth_[o.b] = step_pen_[o.b];
    for (const Overlap& o : fresh_)
      depth_[o.a] = step_pen_[o.a], depth_[o.b] = step_pen_[o.b];
    overlaps_.swap(fresh_);
    for (const std::uint32_t i : moved_)
      active_[i] = 0;
  }
}

// Nothing moved: the overlaps, and with them the deepest and each body's deepest, are the last
// step's, and no body passed through another. What is left: zero displacements, the tunnel
// watch's pairs at rest, and the buckets still refilling after a faster step.
void MetricsRecorder::observe_still(const BodyState& after, int step, bool displacement,
                                    bool overlaps) {
  if (displacement) {
    clear_displacements();
    body_steps_ += dynamic_stepped();
  }
  if (overlaps) {
    deepest_.step = step;
    if (sel_.stability) tunnels_.hold(after);
  }
  if (sel_.stability) {
    std::size_t kept = 0;
    for (const std::size_t i : recovering_) {
      update_slack(after, after, i, step);
      if (slack_[i] < bounds_.allowance[i]) recovering_[kept++] = i;
    }
    recovering_.resize(kept);
  }
}

void MetricsRecorder::visit(const BodyState& before, const BodyState& after, std::size_t i,
                            std::size_t j, int step) {
  // A body out of the world overlaps nothing (meet: both in this state, and not the one leaving
  // and the one entering in its place); one that entered in the step passed through nothing in
  // it (it was not in the state before).
  if (lives_ && !meet(scene_.bodies[i], scene_.bodies[j], step)) return;
  if (filters_ && !scene_.collide(i, j)) return;  // they pass through each other by design
  if (sel_.stability && stepped(i) && stepped(j)) tunnels_.check(before, after, i, j, step);
  const double d = scan().depth(after, i, j);
  const Vec2d hi = scan().half(i), hj = scan().half(j);
  const double scale = std::max(
      {magnitude(after.position[i]), magnitude(after.position[j]), hi.x + hj.x, hi.y + hj.y});
  if (d <= 0.0 || below_resolution(d, scale)) return;
  // A pair created overlapping may stay as deep as it started while it recovers, but not at
  // the end of the run. Two bodies entering together are not judged in the state that places
  // them (placed()), as state 0 is not: no step has pushed them apart yet.
  const double base = scene_.pair_penetration_tolerance(i, j);
  const double tolerance = step < scene_.steps ? std::max(base, initial_depth(i, j)) : base;
  fresh_.push_back({static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(j), d, tolerance});
  if (!sel_.penetration || placed(i, j, step)) return;
  // The first step's worst stands against later ones as bad; within a step, the lowest pair.
  const double ratio = d / tolerance;
  if (ratio > worst_ratio_ || (ratio == worst_ratio_ && worst_.step == step &&
                               pair_key(i, j) < pair_key(worst_.a, worst_.b))) {
    worst_ratio_ = ratio;
    worst_ = {d, i, j, step, tolerance};
  }
}

void MetricsRecorder::settle(int step) {
  deepest_ = PairOverlap{};
  deepest_.step = step;
  double stepped_deepest = 0.0;
  for (const Overlap& o : fresh_) {
    if (o.depth > deepest_.depth ||
        (o.depth == deepest_.depth && pair_key(o.a, o.b) < pair_key(deepest_.a, deepest_.b)))
      deepest_ = {o.depth, o.a, o.b, step, o.tolerance};
    step_pen_[o.a] = std::max(step_pen_[o.a], o.depth);
    step_pen_[o.b] = std::max(step_pen_[o.b], o.depth);
    if (!placed(o.a, o.b, step)) stepped_deepest = std::max(stepped_deepest, o.depth);
  }
  // The run's deepest penetration is an engine's: not an overlap the file placed two bodies in as
  // they enter together (as state 0's overlaps are not), which the state shows all the same.
  max_pen_ = std::max(max_pen_, stepped_deepest);
}

void MetricsRecorder::update_slack(const BodyState& before, const BodyState& after, std::size_t i,
                                   int step) {
  const Vec2d p = after.position[i], v = after.velocity[i], q = before.position[i];
  if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(v.x) || !std::isfinite(v.y)) {
    finite_ = false;
    return;
  }
  const double moved = p.x == q.x && p.y == q.y ? 0.0 : std::hypot(p.x - q.x, p.y - q.y);
  const double speed = moved / dt_;
  if (speed > peak_speed_) peak_speed_ = speed, peak_body_ = i, peak_step_ = step;
  // A leaky bucket: a step slower than the bound gives back what faster ones took, up to
  // the allowance, so that over any stretch of steps a body travels at most the bound times
  // its duration plus the allowance. A step may also push the body out of the overlap it was
  // in, and round it to single precision, without counting against it.
  // Below the floor's top a body has gone through it (tunnelled): the floor's bound no longer
  // holds for it, a fall lasting the run does.
  const double bound = bounds_.floor.below(p) ? bounds_.fallen[i] : bounds_.speed[i];
  if (!std::isfinite(bound)) return;
  const double free = bound * dt_ + depth_[i] + float_resolution(p);
  slack_[i] = std::min(bounds_.allowance[i], slack_[i] + free - moved);
  if (slack_[i] < 0.0 && !blow_up_) {
    blow_up_ = true, blow_up_body_ = i, blow_up_step_ = step, blow_up_speed_ = speed;
    blow_up_bound_ = bound;
  }
}

}  // namespace chainbench
