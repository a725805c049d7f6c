// SPDX-License-Identifier: MIT
#include "judge/expect_relations.h"

#include "support/text_table.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace chainbench {
namespace {

using Kind = Expectation::Kind;
constexpr double kInf = std::numeric_limits<double>::infinity();

// A body's axis-aligned extent in a state: centre and reach from it on each axis.
struct Extent2 {
  Vec2d c, r;
  bool finite = true;
};

Extent2 extent(const Scene& scene, const BodyState& s, std::size_t i) {
  const Vec2d p = s.position[i], h = scene.bodies[i].half_extents;
  const double a = i < s.angle.size() ? s.angle[i] : 0.0;
  Extent2 x;
  x.c = p;
  x.finite = std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(a);
  if (a == 0.0) {
    x.r = h;
  } else {
    const double c = std::abs(std::cos(a)), sn = std::abs(std::sin(a));
    x.r = {h.x * c + h.y * sn, h.x * sn + h.y * c};
  }
  return x;
}

// Separation of two extents along x and y: negative where they overlap on that axis.
Vec2d separation(const Extent2& a, const Extent2& b) {
  return {std::abs(a.c.x - b.c.x) - (a.r.x + b.r.x), std::abs(a.c.y - b.c.y) - (a.r.y + b.r.y)};
}

RelationJudgement finish(double value, double tolerance, bool extra_pass = true) {
  RelationJudgement j;
  j.value = value;
  j.pass = value <= tolerance && extra_pass;
  j.error = j.pass ? 0.0 : std::max(0.0, value - tolerance);
  return j;
}

// The squeeze of body b: for each side (left, right, below, above) the smallest gap to a static or
// kinematic body facing it there (overlapping it along the other axis); the tighter of the two
// opposite pairs decides, by the wider of its two gaps.
RelationJudgement squeeze(const Scene& scene, const Expectation& e, const BodyState& s, int k) {
  const Extent2 a = extent(scene, s, e.body);
  if (!a.finite) return finish(kInf, e.tolerance);
  double gap[4] = {kInf, kInf, kInf, kInf};
  std::size_t who[4] = {0, 0, 0, 0};
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    if (i == e.body || scene.bodies[i].kind == BodyKind::kDynamic || !scene.bodies[i].alive(k) ||
        !scene.collide(i, e.body))
      continue;
    const Extent2 b = extent(scene, s, i);
    if (!b.finite) continue;
    const Vec2d sep = separation(a, b);
    auto offer = [&](int side, double g) {
      if (g < gap[side]) gap[side] = g, who[side] = i;
    };
    if (sep.y < 0.0) offer(b.c.x < a.c.x ? 0 : 1, sep.x);
    if (sep.x < 0.0) offer(b.c.y < a.c.y ? 2 : 3, sep.y);
  }
  const int x_far = gap[0] >= gap[1] ? 0 : 1, y_far = gap[2] >= gap[3] ? 2 : 3;
  const int far = gap[x_far] <= gap[y_far] ? x_far : y_far;
  RelationJudgement j = finish(std::max(0.0, gap[far]), e.tolerance);
  if (std::isfinite(gap[far])) j.other = who[far];
  return j;
}

}  // namespace

RelationJudgement judge_relation(const Scene& scene, const Expectation& e, const BodyState& s,
                                 int k) {
  if (e.kind == Kind::kSqueezed) return squeeze(scene, e, s, k);
  const Extent2 a = extent(scene, s, e.body), b = extent(scene, s, e.other);
  RelationJudgement j;
  if (!a.finite || !b.finite) {
    j = finish(kInf, e.tolerance);
  } else if (e.kind == Kind::kAbove) {
    j = finish((b.c.y + b.r.y) - (a.c.y - a.r.y), e.tolerance);
  } else if (e.kind == Kind::kBelow) {
    j = finish((a.c.y + a.r.y) - (b.c.y - b.r.y), e.tolerance);
  } else {  // kOn: face to face, and over it along x
    const double dy = std::abs((a.c.y - a.r.y) - (b.c.y + b.r.y));
    const double sx = separation(a, b).x;
    if (sx < 0.0) {
      j = finish(dy, e.tolerance);
    } else {  // not over it: a miss of another kind than a distance beyond the tolerance
      j = finish(sx, e.tolerance, false);
      j.error = std::max({sx, dy - e.tolerance, 0.0});
      j.beside = true;
    }
  }
  j.other = e.other;
  return j;
}

PairOverlap deepest_among(const Scene& scene, const Expectation& e, const BodyState& s, int state) {
  PairOverlap deepest;
  for (std::size_t m = 0; m < e.bodies.size(); ++m) {
    for (std::size_t n = m + 1; n < e.bodies.size(); ++n) {
      const std::size_t i = std::min(e.bodies[m], e.bodies[n]);
      const std::size_t k = std::max(e.bodies[m], e.bodies[n]);
      if (!scene.bodies[i].alive(state) || !scene.bodies[k].alive(state)) continue;
      if (!scene.collide(i, k)) continue;  // they pass through each other by design
      const Extent2 a = extent(scene, s, i), b = extent(scene, s, k);
      const Vec2d sep = separation(a, b);
      const double depth = !a.finite || !b.finite       ? kInf
                           : sep.x < 0.0 && sep.y < 0.0 ? std::min(-sep.x, -sep.y)
                                                        : 0.0;
      // The deepest, and of equals the pair listed first.
      if (depth > deepest.depth) deepest.depth = depth, deepest.a = i, deepest.b = k;
    }
  }
  return deepest;
}

std::string describe_relation(const Scene& scene, const ExpectOutcome& o) {
  const Expectation& e = scene.expect[o.index];
  const std::string& body = scene.bodies[e.body].name;
  const std::string other = o.other ? scene.bodies[*o.other].name : std::string("?");
  const int d = digits_apart(o.value, e.tolerance);  // the measure not read as its tolerance
  const std::string limit = concat({", tolerance ", fmt_limit(e.tolerance, d), " m"});
  switch (e.kind) {
    case Kind::kAbove:
      return concat({body, ": bottom ", fmt_g(o.value, d), " m below the top of ", other, limit});
    case Kind::kBelow:
      return concat({body, ": top ", fmt_g(o.value, d), " m above the bottom of ", other, limit});
    case Kind::kOn:
      if (o.beside) {
        return concat({body, ": not over ", other, " along x (",
                       o.value > 0.0 ? concat({fmt_g(o.value, d), " m beside it"})
                                     : std::string("their sides only touch"),
                       "), so not resting on it"});
      }
      return concat({body, ": ", fmt_g(o.value, d), " m from resting on ", other, limit});
    case Kind::kSqueezed:
      return o.other ? concat({body, ": a gap of ", fmt_g(o.value, d), " m to ", other,
                               " on the looser side", limit})
                     : concat({body, ": no static or kinematic body on two opposite sides"});
    default:
      return body;
  }
}

}  // namespace chainbench
