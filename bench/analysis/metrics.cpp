#include "metrics.h"

#include "input_error.h"

#include <algorithm>
#include <bit>
#include <cfloat>
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

namespace {

double magnitude(Vec2d p) {
  return std::max(std::abs(p.x), std::abs(p.y));
}

}  // namespace

double MetricsRecorder::initial_depth(std::size_t i, std::size_t j) const {
  const auto& initial = bounds_.initial_overlaps;
  if (initial.empty()) return 0.0;
  const std::pair<std::uint64_t, double> key{pair_key(i, j), -HUGE_VAL};
  const auto it = std::lower_bound(initial.begin(), initial.end(), key);
  return it != initial.end() && it->first == key.first ? it->second : 0.0;
}

// One unit in the last place of a single-precision coordinate of this magnitude: a float engine
// far from the origin moves in steps of it.
double float_resolution(Vec2d p) {
  const auto m = static_cast<float>(std::min(magnitude(p), 3.0e38));
  return static_cast<double>(std::nextafter(m, HUGE_VALF) - m);
}

bool below_resolution(double value, double magnitude) {
  const double m = std::abs(magnitude);
  if (!std::isfinite(value) || !std::isfinite(m)) return false;
  // One unit in the last place of m (for m = 0, of the smallest normal double).
  const double ulp = m > 0.0 ? std::nextafter(m, HUGE_VAL) - m : DBL_MIN;
  return std::abs(value) <= 2.0 * ulp;
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
  scan.build(state, state);
  PairOverlap deepest;
  deepest.step = step;
  scan.for_each_pair([&](std::size_t i, std::size_t j) {
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
      dt_(scene.dt),
      bounds_(motion_bounds(scene)),
      scan_(scene),
      tunnels_(scene) {
  const std::size_t n = scene.bodies.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (scene.bodies[i].kind == BodyKind::kDynamic) dynamic_.push_back(i);
  }
  slack_ = bounds_.allowance;
  depth_ = bounds_.initial_depth;
  step_efd_.assign(n, 0.0);
  step_pen_.assign(n, 0.0);
  recovering_.reserve(dynamic_.size());
}

// Whether nothing moved in the step from `before` to `after`: every position and angle as it was
// and every velocity zero. Compared as values, so that a NaN always counts as a move. Checked in
// blocks, so that a moving world (where a full pass follows anyway) pays for one block or so.
bool MetricsRecorder::still(const BodyState& before, const BodyState& after) {
  const std::size_t n = after.position.size();
  constexpr std::size_t kBlock = 1024;
  for (std::size_t start = 0; start < n; start += kBlock) {
    const std::size_t end = std::min(n, start + kBlock);
    bool moved = false;
    for (std::size_t i = start; i < end; ++i) {
      moved |= (after.position[i].x != before.position[i].x) |
               (after.position[i].y != before.position[i].y) | (after.angle[i] != before.angle[i]) |
               (after.velocity[i].x != 0.0) | (after.velocity[i].y != 0.0);
    }
    if (moved) return false;
  }
  return true;
}

void MetricsRecorder::update_slack(const BodyState& before, const BodyState& after, std::size_t i,
                                   int step) {
  const Vec2d p = after.position[i], v = after.velocity[i], q = before.position[i];
  if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(v.x) || !std::isfinite(v.y)) {
    finite_ = false;
    return;
  }
  const double moved = std::hypot(p.x - q.x, p.y - q.y);
  const double speed = moved / dt_;
  if (speed > peak_speed_) peak_speed_ = speed, peak_body_ = i, peak_step_ = step;
  // A leaky bucket: a step slower than the bound gives back what faster ones took, up to
  // the allowance, so that over any stretch of steps a body travels at most the bound times
  // its duration plus the allowance. A step may also push the body out of the overlap it was
  // in, and round it to single precision, without counting against it.
  const double bound = bounds_.speed[i];
  if (!std::isfinite(bound)) return;
  const double free = bound * dt_ + depth_[i] + float_resolution(p);
  slack_[i] = std::min(bounds_.allowance[i], slack_[i] + free - moved);
  if (slack_[i] < 0.0 && !blow_up_) {
    blow_up_ = true, blow_up_body_ = i, blow_up_step_ = step, blow_up_speed_ = speed;
  }
}

void MetricsRecorder::observe(const BodyState& before, const BodyState& after, int step,
                              bool per_body, bool depth) {
  const bool displacement = sel_.displacement || per_body;
  const bool overlaps = sel_.penetration || per_body || depth || sel_.stability;
  // A step that moved nothing leaves every figure as the step before left it, so only what
  // changes with the step's number is redone. Not the run's last step: there a pair's tolerance
  // drops to the scene's own (see below), which may make it the worst.
  const bool follows = step == last_step_ + 1 && (!overlaps || overlaps_step_ == last_step_);
  if (follows && step < scene_.steps && still(before, after)) {
    observe_still(after, step, displacement, overlaps);
    return;
  }
  if (displacement) {
    for (const std::size_t i : dynamic_) {
      const double dx = after.position[i].x - before.position[i].x - dt_ * after.velocity[i].x;
      const double dy = after.position[i].y - before.position[i].y - dt_ * after.velocity[i].y;
      const double d = std::sqrt(dx * dx + dy * dy);  // positions stay far below overflow
      step_efd_[i] = d;
      efd_total_ += d;
      efd_max_ = std::max(efd_max_, d);
    }
    body_steps_ += dynamic_.size();
    efd_zero_ = false;
  }
  if (overlaps) {
    scan_.build(before, after);
    deepest_ = PairOverlap{};
    deepest_.step = step;
    std::fill(step_pen_.begin(), step_pen_.end(), 0.0);
    scan_.for_each_pair([&](std::size_t i, std::size_t j) {
      if (sel_.stability) tunnels_.check(before, after, i, j, step);
      const double d = scan_.depth(after, i, j);
      const Vec2d hi = scan_.half(i), hj = scan_.half(j);
      const double scale = std::max(
          {magnitude(after.position[i]), magnitude(after.position[j]), hi.x + hj.x, hi.y + hj.y});
      if (d <= 0.0 || below_resolution(d, scale)) return;
      // A pair created overlapping may stay as deep as it started while it recovers, but not at
      // the end of the run.
      const double base =
          scene_.penetration_tolerance.value_or(0.1 * std::min({hi.x, hi.y, hj.x, hj.y}));
      const double tolerance = step < scene_.steps ? std::max(base, initial_depth(i, j)) : base;
      // Of equal depths the lowest pair, whatever order the scan meets them in.
      if (d > deepest_.depth ||
          (d == deepest_.depth && pair_key(i, j) < pair_key(deepest_.a, deepest_.b)))
        deepest_ = {d, i, j, step, tolerance};
      step_pen_[i] = std::max(step_pen_[i], d);
      step_pen_[j] = std::max(step_pen_[j], d);
      if (sel_.penetration && d / tolerance > worst_ratio_) {
        worst_ratio_ = d / tolerance;
        worst_ = {d, i, j, step, tolerance};
      }
    });
    if (sel_.stability) tunnels_.end_step();
    max_pen_ = std::max(max_pen_, deepest_.depth);
  }
  if (sel_.stability) {
    recovering_.clear();
    for (const std::size_t i : dynamic_) {
      update_slack(before, after, i, step);
      if (slack_[i] < bounds_.allowance[i]) recovering_.push_back(i);
    }
  }
  if (overlaps) {
    depth_ = step_pen_;  // each body's deepest overlap now, for the next step
    overlaps_step_ = step;
  }
  last_step_ = step;
}

// The step moved nothing: every pair overlaps as deep as after the step before, so the deepest
// overlap, each body's deepest and the worst against its tolerance are what they were (a pair's
// tolerance is the same until the last step), and no body moved or passed through another. What
// is left: zero displacements, and the buckets of bodies still refilling after a faster step.
void MetricsRecorder::observe_still(const BodyState& after, int step, bool displacement,
                                    bool overlaps) {
  if (displacement) {
    if (!efd_zero_) std::fill(step_efd_.begin(), step_efd_.end(), 0.0);
    efd_zero_ = true;
    body_steps_ += dynamic_.size();
  }
  if (overlaps) {
    deepest_.step = step;
    if (sel_.stability) tunnels_.hold(after);
    overlaps_step_ = step;
  }
  if (sel_.stability) {
    std::size_t kept = 0;
    for (const std::size_t i : recovering_) {
      update_slack(after, after, i, step);
      if (slack_[i] < bounds_.allowance[i]) recovering_[kept++] = i;
    }
    recovering_.resize(kept);
  }
  last_step_ = step;
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
    m.blow_up_bound = blow_up_ ? bounds_.speed[blow_up_body_] : 0.0;
    for (const std::size_t i : dynamic_) {
      const Vec2d p = last.position[i], p0 = scene_.bodies[i].center;
      const double d = std::hypot(p.x - p0.x, p.y - p0.y);
      if (std::isfinite(d) && d > bounds_.reach[i]) m.escaped.push_back(i);
    }
    m.in_bounds = m.escaped.empty();
    m.tunnelled = tunnels_.count() > 0;
    m.tunnel = tunnels_.first();
    m.tunnel_count = tunnels_.count();
  }
  return m;
}

std::uint64_t position_hash(std::span<const Vec2d> positions) {
  std::uint64_t h = 0xcbf29ce484222325ull;
  auto eat = [&h](double v) {
    const auto bits = std::bit_cast<std::uint64_t>(v);
    for (int k = 0; k < 8; ++k) {
      h ^= (bits >> (8 * k)) & 0xffu;
      h *= 0x100000001b3ull;
    }
  };
  for (const Vec2d& p : positions)
    eat(p.x), eat(p.y);
  return h;
}

std::string hex(std::uint64_t v) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(v));
  return buf;
}

PositionError position_error(const Scene& scene, std::span<const Vec2d> run,
                             std::span<const Vec2d> reference) {
  PositionError e;
  std::size_t n = 0;
  double sum = 0.0;
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    if (scene.bodies[i].kind != BodyKind::kDynamic) continue;
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
