// SPDX-License-Identifier: MIT
#include "judge/metrics.h"

#include "support/fnv1a.h"
#include "support/input_error.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>

namespace chainbench {

MetricSelection parse_metric_selection(const std::string& text) {
  if (text == "all") return {};
  if (text == "none") return MetricSelection::none();
  MetricSelection sel = MetricSelection::none();
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = std::min(text.find(',', start), text.size());
    const std::string name = text.substr(start, comma - start);
    if (name == "displacement") {
      sel.displacement = true;
    } else if (name == "penetration") {
      sel.penetration = true;
    } else if (name == "stability") {
      sel.stability = true;
    } else {
      throw InputError("--metrics: unknown metric \"" + name +
                       "\" (all, none, or a list of displacement, penetration, stability)");
    }
    start = comma + 1;
  }
  return sel;
}

double MetricsRecorder::initial_depth(std::size_t i, std::size_t j) const {
  const auto& initial = bounds_.initial_overlaps;
  if (initial.empty()) return 0.0;
  const std::pair<std::uint64_t, double> key{pair_key(i, j), -HUGE_VAL};
  const auto it = std::lower_bound(initial.begin(), initial.end(), key);
  return it != initial.end() && it->first == key.first ? it->second : 0.0;
}

BodyState initial_state(const Scene& scene) {
  BodyState s(scene.bodies.size());
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    s.position[i] = scene.bodies[i].center;
    s.velocity[i] = scene.bodies[i].kind == BodyKind::kStatic ? Vec2d{} : scene.bodies[i].velocity;
  }
  return s;
}

PairOverlap MetricsRecorder::deepest_overlap(const Scene& scene, const BodyState& state, int step) {
  PairScan scan(scene);
  const bool lifetimes = scene.has_lifetimes();
  if (lifetimes) {  // a body out of the world is left out of the scan, as a lost one is
    BodyState present = state;
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
      if (!scene.bodies[i].alive(step)) present.position[i] = {HUGE_VAL, HUGE_VAL};
    }
    scan.build(present, present);
  } else {
    scan.build(state, state);
  }
  PairOverlap deepest;
  deepest.step = step;
  scan.for_each_pair([&](std::size_t i, std::size_t j) {
    // A body that is not in the world in this state overlaps nothing.
    if (lifetimes && !meet(scene.bodies[i], scene.bodies[j], step)) return;
    const double d = scan.depth(state, i, j);
    if (d > deepest.depth ||
        (d == deepest.depth && d > 0.0 && pair_key(i, j) < pair_key(deepest.a, deepest.b)))
      deepest.depth = d, deepest.a = i, deepest.b = j;
  });
  return deepest;
}

MetricsRecorder::MetricsRecorder(const Scene& scene, MetricSelection selection)
    : sel_(selection),
      scene_(scene),
      presence_(scene),
      lives_(presence_.any()),
      filters_(scene.filters()),
      dt_(scene.dt),
      bounds_(motion_bounds(scene)),
      cache_(scene),
      tunnels_(scene) {
  const std::size_t n = scene.bodies.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (scene.bodies[i].kind == BodyKind::kDynamic) dynamic_.push_back(i);
  }
  slack_ = bounds_.allowance;
  depth_ = bounds_.initial_depth;
  step_efd_.assign(n, 0.0);
  step_pen_.assign(n, 0.0);
  active_.assign(n, 0);
  recovering_.reserve(dynamic_.size());
  merged_.reserve(dynamic_.size());
  // Up to every body each (moved_ and still_ trade buffers), so that no step grows them.
  moved_.reserve(n);
  still_.reserve(n);
  candidates_.reserve(n);
  efd_written_.reserve(dynamic_.size());
  if (lives_) {
    cache_.follow(presence_);
    left_out_.reserve(dynamic_.size());
  }
}

bool MetricsRecorder::escaped(std::size_t i, Vec2d p) const {
  const Vec2d p0 = scene_.bodies[i].center;
  const double d = std::hypot(p.x - p0.x, p.y - p0.y);
  return std::isfinite(d) && d > bounds_.reach[i];
}

void MetricsRecorder::judge_leavers(const BodyState& before) {
  for (const std::uint32_t i : presence_.changed()) {
    if (presence_.was(i) && !presence_.in(i) && scan().dynamic(i) && escaped(i, before.position[i]))
      left_out_.insert(std::upper_bound(left_out_.begin(), left_out_.end(), i), i);
  }
}

Metrics MetricsRecorder::result(const BodyState& last) const {
  Metrics m;
  if (sel_.displacement) {
    m.efd_total = efd_total_;
    m.efd_per_body_step = body_steps_ > 0 ? efd_total_ / static_cast<double>(body_steps_) : 0.0;
    m.efd_max_step = efd_max_;
  }
  if (sel_.penetration) {
    m.max_penetration = max_pen_;
    if (worst_ratio_ > 0.0) m.worst_overlap = worst_;
  }
  if (sel_.stability) {
    m.peak_speed = peak_speed_;
    m.peak_speed_body = peak_body_;
    m.peak_speed_step = peak_step_;
    m.speed_bound =
        bounds_.unbounded.empty() ? std::optional<double>(bounds_.largest_speed) : std::nullopt;
    m.speed_unbounded = bounds_.unbounded;
    m.finite = finite_;
    m.blow_up = blow_up_;
    m.blow_up_body = blow_up_body_;
    m.blow_up_step = blow_up_step_;
    m.blow_up_speed = blow_up_speed_;
    m.blow_up_bound = blow_up_ ? blow_up_bound_ : 0.0;
    // The bodies in the world at the end where they are, those that left where they were last.
    const int end = std::max(last_step_, 0);
    for (const std::size_t i : dynamic_) {
      if (lives_ && !scene_.bodies[i].alive(end)) continue;
      if (escaped(i, last.position[i])) m.escaped.push_back(i);
    }
    if (!left_out_.empty()) {
      const std::size_t mid = m.escaped.size();
      m.escaped.insert(m.escaped.end(), left_out_.begin(), left_out_.end());
      std::inplace_merge(m.escaped.begin(), m.escaped.begin() + static_cast<std::ptrdiff_t>(mid),
                         m.escaped.end());
    }
    m.in_bounds = m.escaped.empty();
    m.tunnelled = tunnels_.count() > 0;
    m.tunnel = tunnels_.first();
    m.tunnel_count = tunnels_.count();
  }
  return m;
}

std::uint64_t position_hash(std::span<const Vec2d> positions) {
  Fnv1a h;
  for (const Vec2d& p : positions) {
    h.add_bits(p.x);
    h.add_bits(p.y);
  }
  return h.value;
}

std::string hex(std::uint64_t v) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(v));
  return buf;
}

PositionError position_error(const Scene& scene, std::span<const Vec2d> run,
                             std::span<const Vec2d> reference, int state) {
  PositionError e;
  std::size_t n = 0;
  double sum = 0.0;
  const bool lives = state >= 0 && scene.has_lifetimes();
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    if (scene.bodies[i].kind != BodyKind::kDynamic) continue;
    if (lives && !scene.bodies[i].alive(state)) continue;
    double d = std::hypot(run[i].x - reference[i].x, run[i].y - reference[i].y);
    if (!std::isfinite(d)) return {HUGE_VAL, HUGE_VAL};  // a lost body: no finite error
    if (below_resolution(d, std::max(magnitude(run[i]), magnitude(reference[i])))) d = 0.0;
    e.max = std::max(e.max, d);
    sum += d * d;
    ++n;
  }
  e.rms = n > 0 ? std::sqrt(sum / static_cast<double>(n)) : 0.0;
  return e;
}

}  // namespace chainbench
