// SPDX-License-Identifier: MIT
#include "judge/verdict.h"

#include "judge/expect_relations.h"

#include "support/text_table.h"

#include <algorithm>
#include <cmath>

namespace chainbench {
namespace {

// Four significant digits below the metre, and every digit down to the millimetre above it, so
// that a point far from the origin still shows where it is.
// With `at_least`, no fewer digits than that (a centre beyond a bound it would read inside).
std::string coordinate(double v, int at_least = 0) {
  const double magnitude = std::abs(v);
  const int digits = magnitude >= 1.0 ? 4 + static_cast<int>(std::log10(magnitude)) : 4;
  return fmt_g(v, std::min(std::max(digits, at_least), 17));
}

std::string point(Vec2d p) {
  return concat({"(", coordinate(p.x), ", ", coordinate(p.y), ")"});
}

std::string at_state(int k) {
  return k == 0 ? std::string("at the start") : concat({"at step ", std::to_string(k)});
}

}  // namespace

const char* to_string(VerdictClass c) {
  switch (c) {
    case VerdictClass::kSkipped:
      return "skipped";
    case VerdictClass::kOk:
      return "ok";
    case VerdictClass::kBudget:
      return "budget";
    case VerdictClass::kPenetrating:
      return "penetrating";
    case VerdictClass::kWrong:
      return "wrong";
    case VerdictClass::kTunnelled:
      return "tunnelled";
    case VerdictClass::kEscaped:
      return "escaped";
    case VerdictClass::kUnstable:
      return "unstable";
    case VerdictClass::kError:
      return "error";
    case VerdictClass::kHang:
      return "hang";
    case VerdictClass::kCrash:
      return "crash";
  }
  return "?";
}

bool Verdict::near_miss() const {
  if (findings.empty()) return false;
  return std::all_of(findings.begin(), findings.end(), [](const Finding& f) { return f.near; });
}

std::string Verdict::str() const {
  if (findings.empty()) return to_string(worst);
  return concat({to_string(worst), ": ", findings.front().detail});
}

std::string describe(const Scene& scene, const ExpectOutcome& o) {
  const Expectation& e = scene.expect[o.index];
  const std::string head = concat({"expect[", std::to_string(o.index), "] ", to_string(e.kind)});
  if (o.state < 0) return concat({head, ": never checked (the run stopped before its window)"});
  const std::string& body = o.body ? scene.bodies[*o.body].name : head;
  // The measure and the limit it is held to, written apart (digits_apart).
  const int d = digits_apart(o.value, o.limit);
  std::string what;
  switch (e.kind) {
    case Expectation::Kind::kCenter:
      what = concat(
          {body, ": ", fmt_g(o.value, d), " m from ", point(e.center), ", at ", point(o.position)});
      break;
    case Expectation::Kind::kMoved: {
      const Vec2d start = scene.bodies[*o.body].center;
      what =
          concat({body, ": ", fmt_g(o.value, d), " m from ",
                  point({start.x + e.moved.x, start.y + e.moved.y}), ", at ", point(o.position)});
      break;
    }
    case Expectation::Kind::kBounds: {
      // The centre to the digits that put it beyond the bound it broke: rounded, 3.34145 past a
      // bound of 3.3414 would read as 3.341, inside it.
      auto apart = [](double v, const std::optional<double>& lo, const std::optional<double>& hi) {
        if (lo && v < *lo) return digits_apart(v, *lo);
        if (hi && v > *hi) return digits_apart(v, *hi);
        return 0;
      };
      const Vec2d p = o.position;
      what = concat({body, ": ", fmt_g(o.value, d), " m outside, at (",
                     coordinate(p.x, apart(p.x, e.min_x, e.max_x)), ", ",
                     coordinate(p.y, apart(p.y, e.min_y, e.max_y)), ")"});
      break;
    }
    case Expectation::Kind::kAtRest:
      what =
          concat({body, ": moving at ", fmt_g(o.value, d), " m/s, limit ", fmt_limit(e.speed, d)});
      break;
    case Expectation::Kind::kNoOverlap:
      what = o.body ? concat({scene.bodies[*o.body].name, " / ", scene.bodies[*o.other].name,
                              ": overlap ", fmt_g(o.value, d), " m, limit ", fmt_limit(e.depth, d)})
                    : concat({"overlap ", fmt_g(o.value, d), " m, limit ", fmt_limit(e.depth, d)});
      break;
    case Expectation::Kind::kAbove:
    case Expectation::Kind::kBelow:
    case Expectation::Kind::kOn:
    case Expectation::Kind::kSqueezed:
      what = describe_relation(scene, o);
      break;
  }
  // The margin against what the entry allows; bounds allow nothing and say it already.
  std::string margin;
  if (!o.pass && e.kind == Expectation::Kind::kBounds && o.near) {
    margin = " (a near miss: within a tenth of 5% of the body's size)";
  } else if (!o.pass && e.kind != Expectation::Kind::kBounds && !o.beside) {
    const char* unit = is_speed(e.kind) ? " m/s" : " m";
    margin = concat({", ", fmt_g(o.margin), unit, " beyond its ", fmt_limit(o.limit, d), unit,
                     o.near ? " (a near miss: within a tenth of it)" : ""});
  }
  return concat({head, " ", what, margin, " ", at_state(o.state)});
}

std::optional<Verdict> judge(const Scene& scene, const Metrics& m,
                             const std::optional<ExpectResult>& expect,
                             std::uint64_t degraded_steps) {
  if (!m.finite || !m.max_penetration) return std::nullopt;
  Verdict v;
  auto name = [&](std::size_t b) { return scene.bodies[b].name; };
  auto add = [&](VerdictClass c, std::string detail, std::vector<std::size_t> bodies = {},
                 int step = -1, std::optional<Vec2d> position = std::nullopt) {
    Finding f;
    f.what = c;
    f.detail = std::move(detail);
    f.bodies = std::move(bodies);
    f.step = step;
    f.position = position;
    v.findings.push_back(std::move(f));
  };
  if (!*m.finite) add(VerdictClass::kUnstable, "a position or velocity became non-finite");
  if (*m.blow_up) {
    add(VerdictClass::kUnstable,
        concat({name(m.blow_up_body), " moved at ", fmt_g(m.blow_up_speed), " m/s at step ",
                std::to_string(m.blow_up_step), ", above its bound ", fmt_g(m.blow_up_bound),
                " m/s"}),
        {m.blow_up_body}, m.blow_up_step);
  }
  if (!m.escaped.empty()) {
    const std::string more = m.escaped.size() > 1
                                 ? concat({" and ", std::to_string(m.escaped.size() - 1), " more"})
                                 : std::string();
    add(VerdictClass::kEscaped,
        concat({name(m.escaped.front()), more, " ended beyond where anything could send it"}),
        m.escaped, scene.steps);
  }
  if (m.tunnel) {
    const std::string all =
        m.tunnel_count > 1 ? concat({" (", std::to_string(m.tunnel_count), " crossings in all)"})
                           : std::string();
    add(VerdictClass::kTunnelled,
        concat({name(m.tunnel->body), " passed through ", name(m.tunnel->through), " ",
                at_state(m.tunnel->step), all}),
        {m.tunnel->body, m.tunnel->through}, m.tunnel->step);
  }
  if (expect && !expect->pass) {
    // The entry furthest from holding first.
    std::vector<const ExpectOutcome*> failed;
    for (const ExpectOutcome& o : expect->entries) {
      if (!o.pass) failed.push_back(&o);
    }
    std::stable_sort(
        failed.begin(), failed.end(), [](const ExpectOutcome* a, const ExpectOutcome* b) {
          return !(a->error <= b->error);  // larger first, never-checked (infinite) first of all
        });
    for (const ExpectOutcome* o : failed) {
      std::vector<std::size_t> bodies;
      if (o->body) bodies.push_back(*o->body);
      if (o->other) bodies.push_back(*o->other);
      const Expectation::Kind kind = scene.expect[o->index].kind;
      const bool located =
          o->body && kind != Expectation::Kind::kAtRest && kind != Expectation::Kind::kNoOverlap;
      add(VerdictClass::kWrong, describe(scene, *o), std::move(bodies), o->state,
          located ? std::optional<Vec2d>(o->position) : std::nullopt);
      if (std::isfinite(o->margin)) {
        v.findings.back().margin = o->margin;
        v.findings.back().tolerance = o->limit;
      }
      v.findings.back().near = o->near;
    }
  }
  if (m.worst_overlap && m.worst_overlap->depth > m.worst_overlap->tolerance) {
    const PairOverlap& w = *m.worst_overlap;
    const double margin = w.depth - w.tolerance;
    const bool near = w.tolerance > 0.0 && margin <= 0.1 * w.tolerance;
    const int d = digits_apart(w.depth, w.tolerance);  // the overlap not read as its tolerance
    add(VerdictClass::kPenetrating,
        concat({name(w.a), " and ", name(w.b), " overlap ", fmt_g(w.depth, d), " m ",
                at_state(w.step), " (", fmt_g(margin), " m beyond its tolerance ",
                fmt_limit(w.tolerance, d), " m", near ? ", a near miss: within a tenth of it" : "",
                ")"}),
        {w.a, w.b}, w.step);
    v.findings.back().margin = margin;
    v.findings.back().tolerance = w.tolerance;
    v.findings.back().near = near;
  }
  if (degraded_steps > 0) {
    add(VerdictClass::kBudget,
        concat({std::to_string(degraded_steps), " step(s) cut short by the budget"}));
  }
  std::stable_sort(v.findings.begin(), v.findings.end(),
                   [](const Finding& a, const Finding& b) { return a.what > b.what; });
  if (!v.findings.empty()) v.worst = v.findings.front().what;
  return v;
}

}  // namespace chainbench
