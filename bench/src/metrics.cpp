#include "metrics.h"

#include "input_error.h"

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

MetricsRecorder::MetricsRecorder(const Scene& scene, MetricSelection selection)
    : sel_(selection), dt_(scene.dt) {
  double fastest = 0.0, drive = 0.0, restitution = scene.restitution, gravity_scale = 0.0;
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const SceneBody& b = scene.bodies[i];
    const double speed = std::hypot(b.velocity.x, b.velocity.y);
    if (b.kind == BodyKind::kDynamic) {
      dynamic_.push_back(i);
      fastest = std::max(fastest, speed);
      gravity_scale = std::max(gravity_scale, std::abs(b.gravity_scale));
    } else if (b.kind == BodyKind::kKinematic) {
      drive = std::max(drive, speed);
    }
    restitution = std::max(restitution, scene.restitution_of(b));
  }
  for (const Driver& d : scene.drivers)
    drive = std::max(drive, std::hypot(d.velocity.x, d.velocity.y));
  // A body can fall for the whole run, keep its start speed, and be hit by something driven,
  // bouncing off it at up to (1 + e) times its speed. A quarter more, plus 1 m/s, for slack.
  const double fall =
      std::hypot(scene.gravity.x, scene.gravity.y) * gravity_scale * scene.dt * scene.steps;
  speed_bound_ = 1.25 * ((1.0 + restitution) * drive + fastest + fall) + 1.0;
  const Extent e = initial_extent(scene);
  center_ = e.center;
  bound_radius_ = 10.0 * std::max(e.radius, 1.0);
  if (sel_.penetration) scan_.emplace(scene);
  step_efd_.assign(scene.bodies.size(), 0.0);
  step_pen_.assign(scene.bodies.size(), 0.0);
}

void MetricsRecorder::observe(const BodyState& before, const BodyState& after, bool per_body) {
  if (sel_.displacement || per_body) {
    for (const std::size_t i : dynamic_) {
      const double dx = after.position[i].x - before.position[i].x - dt_ * after.velocity[i].x;
      const double dy = after.position[i].y - before.position[i].y - dt_ * after.velocity[i].y;
      const double d = std::sqrt(dx * dx + dy * dy);  // positions stay far below overflow
      step_efd_[i] = d;
      efd_total_ += d;
      efd_max_ = std::max(efd_max_, d);
    }
    body_steps_ += dynamic_.size();
  }
  if (scan_) {
    max_pen_ = std::max(max_pen_, scan_->deepest(after, per_body ? std::span<double>(step_pen_)
                                                                 : std::span<double>()));
  }
  if (sel_.stability) {
    for (const std::size_t i : dynamic_) {
      const Vec2d p = after.position[i], v = after.velocity[i];
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(v.x) ||
          !std::isfinite(v.y)) {
        finite_ = false;
        continue;
      }
      peak_speed_ = std::max(peak_speed_, std::sqrt(v.x * v.x + v.y * v.y));
      const double ox = p.x - center_.x, oy = p.y - center_.y;
      if (ox * ox + oy * oy > bound_radius_ * bound_radius_) in_bounds_ = false;
    }
  }
}

Metrics MetricsRecorder::result() const {
  Metrics m;
  if (sel_.displacement) {
    m.efd_total = efd_total_;
    m.efd_per_body_step = body_steps_ > 0 ? efd_total_ / static_cast<double>(body_steps_) : 0.0;
    m.efd_max_step = efd_max_;
  }
  if (sel_.penetration) m.max_penetration = max_pen_;
  if (sel_.stability) {
    m.peak_speed = peak_speed_;
    m.speed_bound = speed_bound_;
    m.finite = finite_;
    m.in_bounds = in_bounds_;
    m.blow_up = peak_speed_ > speed_bound_;
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
    const double d = std::hypot(run[i].x - reference[i].x, run[i].y - reference[i].y);
    if (!std::isfinite(d)) return {HUGE_VAL, HUGE_VAL};  // a lost body: no finite error
    e.max = std::max(e.max, d);
    sum += d * d;
    ++n;
  }
  e.rms = n > 0 ? std::sqrt(sum / static_cast<double>(n)) : 0.0;
  return e;
}

}  // namespace chainbench
