// SPDX-License-Identifier: MIT
#include "judge/expectations.h"

#include "judge/expect_relations.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace chainbench {
namespace {

using Kind = Expectation::Kind;

bool finite(Vec2d p) {
  return std::isfinite(p.x) && std::isfinite(p.y);
}

// How far p lies outside the bounds of e (0 inside). Within 1e-9 of a bound (times the bound's
// magnitude beyond 1 m) is on it: the engines' own arithmetic leaves that much, and the chain
// solver counts overlaps that shallow as contact.
double outside(const Expectation& e, Vec2d p) {
  auto beyond = [](double v, const std::optional<double>& lo, const std::optional<double>& hi) {
    auto slack = [](double bound) { return 1e-9 * std::max(1.0, std::abs(bound)); };
    if (lo && v < *lo - slack(*lo)) return *lo - v;
    if (hi && v > *hi + slack(*hi)) return v - *hi;
    return 0.0;
  };
  return std::hypot(beyond(p.x, e.min_x, e.max_x), beyond(p.y, e.min_y, e.max_y));
}

}  // namespace

ExpectationCheck::ExpectationCheck(const Scene& scene) : scene_(scene) {
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    if (scene.bodies[i].kind == BodyKind::kDynamic) dynamic_.push_back(i);
  }
  outcomes_.resize(scene.expect.size());
  for (std::size_t k = 0; k < outcomes_.size(); ++k)
    outcomes_[k].index = k;
  // Each entry's window of states [first, last], as counts opened and closed along the run; an
  // at_rest entry also needs the state before its window, to measure the first step's speed.
  const auto states = static_cast<std::size_t>(std::max(scene.steps, 0)) + 1;
  std::vector<int> state_count(states + 1, 0), depth_count(states + 1, 0);
  auto open = [&](std::vector<int>& count, int first, int last) {
    first = std::max(first, 0);
    last = std::min(last, static_cast<int>(states) - 1);
    if (first > last) return;
    ++count[static_cast<std::size_t>(first)];
    --count[static_cast<std::size_t>(last) + 1];
  };
  for (const Expectation& e : scene.expect) {
    const int first = e.first_state(scene.steps), last = e.last_state(scene.steps);
    open(state_count, first, last);
    if (e.kind == Kind::kAtRest) open(state_count, first - 1, last - 1);
    if (e.kind == Kind::kNoOverlap && e.bodies.empty()) open(depth_count, first, last);
  }
  needs_state_.resize(states);
  needs_depth_.resize(states);
  long open_states = 0, open_depths = 0;
  for (std::size_t k = 0; k < states; ++k) {
    open_states += state_count[k];
    open_depths += depth_count[k];
    needs_state_[k] = open_states != 0;
    needs_depth_[k] = open_depths != 0;
  }
}

bool ExpectationCheck::needs_state(int k) const {
  return k >= 0 && static_cast<std::size_t>(k) < needs_state_.size() &&
         needs_state_[static_cast<std::size_t>(k)] != 0;
}

bool ExpectationCheck::needs_depth(int k) const {
  return k >= 0 && static_cast<std::size_t>(k) < needs_depth_.size() &&
         needs_depth_[static_cast<std::size_t>(k)] != 0;
}

// Keeps the state with the largest error, or, while every state passes, the largest value: the
// state nearest to failing (the latest of equals).
bool ExpectationCheck::judge(ExpectOutcome& o, double value, double error, bool pass, int k) {
  // A failed state outranks every passed one of the same error (an `on` whose sides only touch
  // fails with error 0), and a passed state never replaces a failed one.
  const bool tie = error == o.error && value >= o.value && !(pass && !o.pass);
  const bool worse = o.state < 0 || !(error <= o.error) || (!pass && o.pass) || tie;
  if (worse) o.value = value, o.error = error, o.state = k;
  o.pass = o.pass && pass;
  return worse;
}

void ExpectationCheck::observe(int k, const BodyState& state, const BodyState* previous,
                               const PairOverlap* deepest) {
  const double inf = std::numeric_limits<double>::infinity();
  for (std::size_t n = 0; n < scene_.expect.size(); ++n) {
    const Expectation& e = scene_.expect[n];
    if (k < e.first_state(scene_.steps) || k > e.last_state(scene_.steps)) continue;
    ExpectOutcome& o = outcomes_[n];
    if (e.kind == Kind::kNoOverlap) {
      // Named bodies: their own pairs, whatever their kinds; else the run's deepest pair.
      const PairOverlap among =
          e.bodies.empty() ? PairOverlap{} : deepest_among(scene_, e, state, k);
      const PairOverlap* pair = e.bodies.empty() ? deepest : &among;
      const double depth = pair ? pair->depth : 0.0;
      if (judge(o, depth, std::max(0.0, depth - e.depth), depth <= e.depth, k)) {
        o.rms = o.error;
        if (depth > 0.0) o.body = pair->a, o.other = pair->b;
      }
      continue;
    }
    if (is_relation(e.kind)) {
      const RelationJudgement r = judge_relation(scene_, e, state, k);
      if (judge(o, r.value, r.error, r.pass, k)) {
        o.body = e.body, o.other = r.other, o.position = state.position[e.body];
        o.beside = r.beside;
        o.rms = o.error;
      }
      continue;
    }
    const std::size_t single[1] = {e.body};
    const bool all = e.body == Expectation::kEveryDynamic;
    const std::size_t* begin = all ? dynamic_.data() : single;
    const std::size_t* end = all ? dynamic_.data() + dynamic_.size() : single + 1;
    double sum_sq = 0.0;
    std::size_t judged = 0;
    for (const std::size_t* b = begin; b != end; ++b) {
      // "*" judges the bodies in the world in this state (validate() keeps a named body's window
      // within its life).
      if (!scene_.bodies[*b].alive(k)) continue;
      ++judged;
      const Vec2d p = state.position[*b];
      double value = 0.0, error = 0.0;
      bool pass = true;
      switch (e.kind) {
        case Kind::kCenter:
        case Kind::kMoved: {
          const Vec2d start = scene_.bodies[*b].center;
          const Vec2d c =
              e.kind == Kind::kCenter ? e.center : Vec2d{start.x + e.moved.x, start.y + e.moved.y};
          value = finite(p) ? std::hypot(p.x - c.x, p.y - c.y) : inf;
          const double scale =
              std::max({std::abs(p.x), std::abs(p.y), std::abs(c.x), std::abs(c.y)});
          if (below_resolution(value, scale)) value = 0.0;
          error = value;
          pass = value <= e.tolerance;
          break;
        }
        case Kind::kBounds:
          value = finite(p) ? outside(e, p) : inf;
          error = value;
          pass = value == 0.0;
          break;
        case Kind::kAtRest: {
          const Vec2d v = scene_.bodies[*b].velocity;
          // In the state it enters in a body has no step behind it: its speed is its own.
          const BodyState* before = scene_.bodies[*b].alive(k - 1) ? previous : nullptr;
          const Vec2d q = before ? before->position[*b] : p;
          value = !finite(p) ? inf
                  : before   ? std::hypot(p.x - q.x, p.y - q.y) / scene_.dt
                             : std::hypot(v.x, v.y);
          error = std::max(0.0, value - e.speed);
          pass = value <= e.speed;
          break;
        }
        default:  // judged above
          break;
      }
      if (judge(o, value, error, pass, k)) o.body = *b, o.position = p;
      sum_sq += error * error;
    }
    if (o.state == k) {  // this state is the entry's worst
      o.bodies = judged;
      o.rms = o.bodies > 0 ? std::sqrt(sum_sq / static_cast<double>(o.bodies)) : 0.0;
    }
  }
}

ExpectResult ExpectationCheck::result() const {
  ExpectResult r;
  r.entries = outcomes_;
  bool all_near = true;
  for (ExpectOutcome& o : r.entries) {
    const Expectation& e = scene_.expect[o.index];
    if (o.state < 0) o.pass = false;  // the run stopped before the entry's window
    const double error = std::isfinite(o.error) ? o.error : HUGE_VAL;
    switch (e.kind) {
      case Kind::kCenter:
      case Kind::kMoved:
        o.limit = e.tolerance;
        o.margin = o.value - e.tolerance;
        break;
      case Kind::kBounds:
        o.limit = 0.0;
        o.margin = o.pass ? 0.0 : o.error;
        break;
      case Kind::kAtRest:
        o.limit = e.speed;
        o.margin = o.value - e.speed;
        break;
      case Kind::kNoOverlap:
        o.limit = e.depth;
        o.margin = o.value - e.depth;
        break;
      case Kind::kAbove:
      case Kind::kBelow:
      case Kind::kOn:
      case Kind::kSqueezed:
        // A failed `on` off the other along x is at least that far beyond.
        o.limit = e.tolerance;
        o.margin = o.pass ? o.value - e.tolerance : o.error;
        break;
    }
    if (o.state < 0) o.margin = HUGE_VAL;
    // Bounds allow nothing: a miss is near against the share of the body's size that is visibly
    // wrong (5% of its smaller edge, as the default penetration tolerance), 6e-8 m not being 2 m.
    double scale = o.limit;
    if (e.kind == Kind::kBounds && o.body) {
      const Vec2d h = scene_.bodies[*o.body].half_extents;
      scale = 0.05 * 2.0 * std::min(h.x, h.y);
    }
    o.near = !o.pass && !o.beside && scale > 0.0 && o.margin <= 0.1 * scale;
    if (is_speed(e.kind)) {
      r.has_speed = true;
      r.max_speed_error = std::max(r.max_speed_error, error);
      r.speed_pass = r.speed_pass && o.pass;
    } else {
      r.has_position = true;
      r.max_error = std::max(r.max_error, error);
      r.position_pass = r.position_pass && o.pass;
    }
    r.pass = r.pass && o.pass;
    if (!o.pass) all_near = all_near && o.near;
  }
  r.near_miss = !r.pass && all_near;
  return r;
}

}  // namespace chainbench
