// SPDX-License-Identifier: MIT
// Level scenes: what a platformer's levels ask of a resolver. Tile floors with seams, fast falling
// crates, a character walking off a ledge, a crate riding a moving platform and one sliding on a
// rough floor. Metres, gravity (0, -10), dt 1/60 unless set; each states its analytic answer.
#include "scenes/scene_library.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace chainbench {
namespace {

using build::box;

// Static tiles side by side on [x0, x1], cut at `cuts`, their top face at `top`, `thick` deep.
void tiles(Scene& s, const std::vector<double>& edges, double top, double thick) {
  for (std::size_t i = 0; i + 1 < edges.size(); ++i) {
    const double half = 0.5 * (edges[i + 1] - edges[i]);
    box(s, build::label("tile", static_cast<int>(i)), BodyKind::kStatic,
        {edges[i] + half, top - 0.5 * thick}, {half, 0.5 * thick});
  }
}

// A 0.5 m box (5 kg) sliding at `speed` over the join of two flush floor tiles, starting
// `phase` m past the join on the near side. Mirrored by `direction` = -1 (leftwards, the case a
// contact order decides) or +1. Frictionless: nothing slows it, so after n steps it is
// speed n dt further on, resting at y = 0.25.
Scene seam_slide(const SceneParams& p) {
  Scene s;
  s.name = "seam_slide";
  const double dir = p.get("direction") < 0 ? -1.0 : 1.0;
  // Leftwards: tiles [-4, 0] and [0, 2]; rightwards, their mirror image.
  tiles(s, dir < 0 ? std::vector<double>{-4.0, 0.0, 2.0} : std::vector<double>{-2.0, 0.0, 4.0}, 0.0,
        1.0);
  const double x0 = -dir * p.get("phase");
  const std::size_t b = box(s, "box", BodyKind::kDynamic, {x0, 0.25}, {0.25, 0.25}, 5.0);
  s.bodies[b].velocity = {dir * p.get("speed"), 0.0};
  const double travel = p.get("speed") * p.get("dt") * p.count("steps");
  const double tolerance = build::kVisible * 0.5;
  // Past the far tile's end it would fall: the answer holds while it stays on the tiles.
  const double end = dir < 0 ? -4.0 + 0.25 : 4.0 - 0.25;
  const double x = dir < 0 ? std::max(x0 + dir * travel, end) : std::min(x0 + dir * travel, end);
  if (x == x0 + dir * travel) s.expect.push_back(build::expect_center(b, {x, 0.25}, tolerance));
  // Never snagged: it neither sinks into the floor nor rises off it on the way.
  Expectation level =
      build::expect_bounds(b, std::nullopt, 0.25 - tolerance, std::nullopt, 0.25 + tolerance);
  level.from_step = 0;
  s.expect.push_back(level);
  return s;
}

// A 0.5 m crate dropped (or thrown down at `speed`) at x onto two 0.1 m tiles, [-1, 0] and
// [0, 1] with their top at y = 0.05: it lands where it fell, at (x, 0.3), never pushed sideways.
Scene seam_landing(const SceneParams& p) {
  Scene s;
  s.name = "seam_landing";
  tiles(s, {-1.0, 0.0, 1.0}, 0.05, 0.1);
  const double x = p.get("x");
  const std::size_t c = box(s, "crate", BodyKind::kDynamic, {x, 1.35}, {0.25, 0.25}, 1.0);
  s.bodies[c].velocity = {0.0, -p.get("speed")};
  const double tolerance = build::kVisible * 0.5;
  const double fall = 1.05;  // from y = 1.35 to 0.3
  const double v = p.get("speed"), g = 10.0;
  const double t_land = (-v + std::sqrt(v * v + 2.0 * g * fall)) / g;
  if (t_land + 2.0 * p.get("dt") <= p.get("dt") * p.count("steps"))
    s.expect.push_back(build::expect_center(c, {x, 0.3}, tolerance));
  Expectation straight =
      build::expect_bounds(c, x - tolerance, 0.3 - tolerance, x + tolerance, std::nullopt);
  straight.from_step = 0;
  s.expect.push_back(straight);
  return s;
}

// A 0.5 m crate falling at `speed` onto a 0.1 m static slab from 3 m above it: it stops on the
// slab at (0, 0.3), whatever the speed, and is never below it.
Scene fast_drop(const SceneParams& p) {
  Scene s;
  s.name = "fast_drop";
  box(s, "slab", BodyKind::kStatic, {0.0, 0.0}, {2.0, 0.05});
  const std::size_t c = box(s, "crate", BodyKind::kDynamic, {0.0, 3.3}, {0.25, 0.25}, 1.0);
  s.bodies[c].velocity = {0.0, -p.get("speed")};
  const double tolerance = build::kVisible * 0.5;
  s.expect.push_back(build::expect_center(c, {0.0, 0.3}, tolerance));
  Expectation above =
      build::expect_bounds(c, std::nullopt, 0.3 - tolerance, std::nullopt, std::nullopt);
  above.from_step = 0;
  s.expect.push_back(above);
  return s;
}

// A character (0.5 m wide, 1 m tall) walking at `speed` towards the edge of a floor ending at
// x = 0, its horizontal speed held by a driver and its vertical left to gravity: past the edge it
// falls as a thrown body does. Engines differ by one step in when support ends (contacts read
// before or after the move) and integrate velocity and position in either order, so the height
// is bounded by falls of m - 1 and m + 1 steps, m counted from the first state off the edge.
Scene ledge_walk(const SceneParams& p) {
  Scene s;
  s.name = "ledge_walk";
  box(s, "floor", BodyKind::kStatic, {-5.0, -0.5}, {5.0, 0.5});
  const std::size_t c = box(s, "character", BodyKind::kDynamic, {-1.0, 0.5}, {0.25, 0.5}, 1.0);
  Driver walk;
  walk.body = c;
  walk.velocity = {p.get("speed"), 0.0};
  walk.hold_y = false;
  s.drivers.push_back(walk);
  const double dt = p.get("dt"), v = p.get("speed");
  const int n = p.count("steps");
  const double x = -1.0 + v * dt * n;
  // The first state whose left edge is past the floor's end. When the edge reaches the corner
  // exactly at a step (1.25 / (v dt) a whole number), rounding decides whether that state is on
  // or off the floor, so both are right: the bounds take the earlier and the later of the two.
  const double steps_to_edge = v > 0 ? 1.25 / (v * dt) : n + 1.0;
  const int off_early = static_cast<int>(std::floor(steps_to_edge * (1.0 - 1e-9))) + 1;
  const int off_late = static_cast<int>(std::floor(steps_to_edge * (1.0 + 1e-9))) + 1;
  const int m_most = std::max(0, n - off_early), m_least = std::max(0, n - off_late);
  const double g = 10.0;
  auto fallen = [&](int k) { return k <= 0 ? 0.0 : g * dt * dt * k * (k + 1) / 2.0; };
  const double low = 0.5 - fallen(m_most + 1);
  const double high = 0.5 - (m_least > 0 ? fallen(m_least - 2) : 0.0);
  // x is driven exactly; an engine in single precision rounds each step's move by up to half a
  // unit in the last place of float at |x| (2^-24 |x|), n times.
  const double x_tolerance = 1e-6 + n * std::ldexp(std::abs(x) + std::abs(v * dt), -24);
  s.expect.push_back(
      build::expect_bounds(c, x - x_tolerance, low - 1e-6, x + x_tolerance, high + 1e-6));
  return s;
}

// A box (edge `edge`, 1 kg, frictionless) moving at `speed` from x = -2 - edge / 2 towards a gap
// `gap` wide between two grounds whose tops are at y = 0, held at that speed by a driver
// (driven = 1, a character) or sliding free (driven = 0); a pit floor at y = -3. A box wider than
// the gap always has ground under it, so it crosses at its speed and never drops. One narrower
// by more than two steps' travel is unsupported for a whole step: it falls in and ends on the
// pit floor against the far ground's side. In between, a step cannot tell sinking for part of a
// step from falling (docs/limits.md): nothing is expected of the crossing.
Scene gap_cross(const SceneParams& p) {
  Scene s;
  s.name = "gap_cross";
  const double edge = p.get("edge"), gap = p.get("gap"), v = p.get("speed"), dt = p.get("dt");
  const double half = 0.5 * edge, g = 10.0, pit = 3.0;
  const double x0 = -2.0 - half, t = dt * p.count("steps");
  // The far ground reaches a metre past where the box's speed takes it (at most 1,000 km).
  const double far = std::clamp(0.5 * (x0 + v * t + half + 1.0 - gap), 6.0, 5.0e5);
  const bool stays = x0 + v * t + half <= gap + 2.0 * far;
  box(s, "near", BodyKind::kStatic, {-6.0, -0.5 * pit}, {6.0, 0.5 * pit});
  box(s, "far", BodyKind::kStatic, {gap + far, -0.5 * pit}, {far, 0.5 * pit});
  box(s, "pit_floor", BodyKind::kStatic, {0.5 * gap, -pit - 0.5}, {0.5 * gap + 12.0, 0.5});
  const std::size_t b = box(s, "box", BodyKind::kDynamic, {x0, half}, {half, half}, 1.0);
  s.bodies[b].velocity = {v, 0.0};
  if (p.get("driven") != 0) {
    Driver drive;
    drive.body = b;
    drive.velocity = {v, 0.0};
    drive.hold_y = false;
    s.drivers.push_back(drive);
  }
  const double tolerance = build::kVisible * 0.5;
  // The answers are a frictionless, inelastic box's: with friction or bounces nothing is expected.
  const bool plain = p.get("friction") == 0.0 && p.get("restitution") == 0.0;
  if (!plain) return s;
  if (gap <= edge && stays) {
    s.expect.push_back(build::expect_center(b, {x0 + v * t, half}, tolerance));
    // A box exactly as wide as the gap may dip one step's gravity sink, g dt^2, for one step.
    Expectation level = build::expect_bounds(b, std::nullopt, half - tolerance - g * dt * dt,
                                             std::nullopt, std::nullopt);
    level.from_step = 0;
    s.expect.push_back(level);
  } else if (gap >= edge + 2.0 * v * dt && v > 0.0) {
    // Past the near edge, then at most the fall to the pit floor and the rest of the gap to cross,
    // a step's travel and 0.25 s to spare.
    const double fall = std::sqrt(2.0 * pit / g);
    if (t >= (2.0 + gap) / v + fall + 0.25 + dt)
      s.expect.push_back(build::expect_center(b, {gap - half, -pit + half}, tolerance));
  }
  return s;
}

// A character (0.5 m wide, 1 m tall, category 2) driven at `speed` along a floor through a row of
// `crates` 0.5 m crates (category 4) that collide with the floor but not with it (their masks
// leave each other's category out), to a wall at x = 6 that collides with everything. The crates
// rest where they were built, the character passes through them at its speed and stops against
// the wall: x = min(-1 + v t, 5.75), resting at y = 0.5; no pair that does not collide is judged.
Scene filter_walk(const SceneParams& p) {
  Scene s;
  s.name = "filter_walk";
  box(s, "floor", BodyKind::kStatic, {0.0, -0.5}, {10.0, 0.5});
  box(s, "wall", BodyKind::kStatic, {6.5, 2.0}, {0.5, 2.0});
  const std::size_t c = box(s, "character", BodyKind::kDynamic, {-1.0, 0.5}, {0.25, 0.5}, 1.0);
  s.bodies[c].category_bits = 0x0002;
  s.bodies[c].mask_bits = 0xFFFF & ~0x0004;
  Driver walk;
  walk.body = c;
  walk.velocity = {p.get("speed"), 0.0};
  walk.hold_y = false;
  s.drivers.push_back(walk);
  const int n = p.count("crates");
  for (int i = 0; i < n; ++i) {
    const std::size_t k =
        box(s, build::label("crate", i), BodyKind::kDynamic, {0.75 * i, 0.25}, {0.25, 0.25}, 2.0);
    s.bodies[k].category_bits = 0x0004;
    s.bodies[k].mask_bits = 0xFFFF & ~0x0002;
    s.expect.push_back(build::expect_center(k, {0.75 * i, 0.25}, build::kVisible * 0.25));
  }
  const double t = p.get("dt") * p.count("steps");
  const double x = std::min(-1.0 + p.get("speed") * t, 6.0 - 0.25);
  s.expect.push_back(build::expect_center(c, {x, 0.5}, build::kVisible * 0.5));
  return s;
}

// How far a friction stop or catch-up may land from the analytic one: by one step's travel,
// v dt (an engine whose contact acts in the step after the move travels a whole step more;
// semi-implicit integration lands within v dt / 2), with 5% for rounding, never under 2 cm.
double one_step_slip(double v, double dt) {
  return std::max(0.02, 1.05 * std::abs(v) * dt);
}

// A crate on a kinematic platform that starts moving at `speed`: kinetic friction accelerates it
// at mu g until it moves with the platform, so it slips v^2 / (2 mu g) (0.2 m at 2 m/s, mu = 1)
// and rides on. Frictionless, it stays where it was while the platform slides under it.
Scene platform_ride(const SceneParams& p) {
  Scene s;
  s.name = "platform_ride";
  const std::size_t platform = box(s, "platform", BodyKind::kKinematic, {0.0, -0.25}, {3.0, 0.25});
  const double v = p.get("speed"), mu = p.get("mu"), g = 10.0;
  s.bodies[platform].velocity = {v, 0.0};
  s.bodies[platform].friction = mu;
  const std::size_t c = box(s, "crate", BodyKind::kDynamic, {0.0, 0.25}, {0.25, 0.25}, 1.0);
  s.bodies[c].friction = mu;
  // Until it catches up, at t = v / (mu g), it moves mu g t^2 / 2; after, with the platform.
  const double t = p.get("dt") * p.count("steps");
  // Frictionless, it never catches up: it stays where it was.
  const double catch_up = mu > 0 ? v / (mu * g) : std::numeric_limits<double>::infinity();
  const double moved = t >= catch_up ? v * t - v * v / (2.0 * mu * g) : 0.5 * mu * g * t * t;
  // While it is still on the platform (its left end is at -3 + v t), within one step's travel.
  if (moved >= -3.0 + v * t + 0.25) {
    s.expect.push_back(build::expect_moved(c, {moved, 0.0}, one_step_slip(v, p.get("dt"))));
  }
  return s;
}

// A crate sliding at `speed` on a floor with friction `mu`: it stops after v^2 / (2 mu g)
// (0.4 m from 2 m/s at mu = 0.5), within one step's travel.
Scene rough_slide(const SceneParams& p) {
  Scene s;
  s.name = "rough_slide";
  const std::size_t floor = box(s, "floor", BodyKind::kStatic, {0.0, -0.5}, {10.0, 0.5});
  const double v = p.get("speed"), mu = p.get("mu"), g = 10.0;
  s.bodies[floor].friction = mu;
  const std::size_t c = box(s, "crate", BodyKind::kDynamic, {-5.0, 0.25}, {0.25, 0.25}, 1.0);
  s.bodies[c].friction = mu;
  s.bodies[c].velocity = {v, 0.0};
  const double t = p.get("dt") * p.count("steps");
  const double stop = mu > 0 ? v / (mu * g) : t;
  const double d = t >= stop ? v * v / (2.0 * mu * g) : v * t - 0.5 * mu * g * t * t;
  if (-5.0 + d <= 10.0 - 0.25) {
    s.expect.push_back(build::expect_moved(c, {d, 0.0}, one_step_slip(v, p.get("dt"))));
  }
  return s;
}

// A crate set down at rest on a static conveyor whose belt runs at `speed`: friction mu
// accelerates it at mu g until it moves with the belt, so it slips v^2 / (2 mu g) and rides on
// (as on a platform moving at v, platform_ride), within one step's travel. Frictionless, it stays.
Scene conveyor(const SceneParams& p) {
  Scene s;
  s.name = "conveyor";
  const double v = p.get("speed"), mu = p.get("mu"), g = 10.0;
  const std::size_t belt = box(s, "belt", BodyKind::kStatic, {0.0, -0.25}, {20.0, 0.25});
  s.bodies[belt].surface_velocity = {v, 0.0};
  s.bodies[belt].friction = mu;
  const std::size_t c = box(s, "crate", BodyKind::kDynamic, {-10.0, 0.25}, {0.25, 0.25}, 1.0);
  s.bodies[c].friction = mu;
  const double t = p.get("dt") * p.count("steps");
  const double catch_up = mu > 0 ? std::abs(v) / (mu * g) : std::numeric_limits<double>::infinity();
  const double moved = t >= catch_up ? v * t - std::copysign(v * v / (2.0 * mu * g), v)
                                     : std::copysign(0.5 * mu * g * t * t, v);
  if (std::abs(-10.0 + moved) <= 20.0 - 0.25)  // still on the belt
    s.expect.push_back(build::expect_moved(c, {moved, 0.0}, one_step_slip(v, p.get("dt"))));
  return s;
}

std::size_t three(const SceneParams&) {
  return 3;
}
std::size_t two(const SceneParams&) {
  return 2;
}
std::size_t four(const SceneParams&) {
  return 4;
}

}  // namespace

std::vector<SceneRecipe> level_scenes() {
  return {
      {"seam_slide",
       "level",
       "a box sliding over the join of two flush floor tiles: it must not snag",
       {{"direction", -1, -1, 1, true, "-1 leftwards, 1 rightwards"},
        {"speed", 5, 0, 1000, false, "m/s"},
        {"phase", 0.33233, 0, 2, false, "start past the join, m"}},
       seam_slide,
       three,
       30},
      {"seam_landing",
       "level",
       "a crate dropped next to the join of two tiles: it lands where it fell",
       {{"x", 0.2, -0.75, 0.75, false, "where it falls, m"},
        {"speed", 0, 0, 1000, false, "thrown down at, m/s"}},
       seam_landing,
       three,
       60},
      {"fast_drop",
       "level",
       "a crate falling fast onto a thin slab: it stops on it",
       {{"speed", 25, 0, 10000, false, "m/s"}},
       fast_drop,
       two,
       60},
      {"ledge_walk",
       "level",
       "a character walking off a ledge, its horizontal speed held: it falls",
       {{"speed", 4, 0, 100, false, "walking speed, m/s"}},
       ledge_walk,
       two,
       60},
      {"platform_ride",
       "level",
       "a crate on a platform that starts moving sideways: friction carries it",
       {{"speed", 2, 0, 100, false, "platform speed, m/s"},
        {"mu", 1, 0, 10, false, "friction of crate and platform"}},
       platform_ride,
       two,
       60},
      {"rough_slide",
       "level",
       "a crate sliding on a rough floor: friction stops it",
       {{"speed", 2, 0, 100, false, "m/s"},
        {"mu", 0.5, 0, 10, false, "friction of crate and floor"}},
       rough_slide,
       two,
       60},
      {"gap_cross",
       "level",
       "a box crossing a gap between two level grounds: no wider than the box, it crosses",
       {{"edge", 1, 0.05, 2, false, "box edge, m"},
        {"gap", 1, 0, 4, false, "gap between the grounds, m"},
        {"speed", 2, 0, 100, false, "m/s"},
        {"driven", 1, 0, 1, true, "1: a driver holds its x speed; 0: it slides free"}},
       gap_cross,
       four,
       180},
      {"conveyor",
       "level",
       "a crate set down on a running conveyor belt: it slips, then rides at the belt's speed",
       {{"speed", 2, -100, 100, false, "belt speed along x, m/s"},
        {"mu", 1, 0, 10, false, "friction of crate and belt"}},
       conveyor,
       two,
       60},
      {"filter_walk",
       "level",
       "a character walking through crates it does not collide with (filtering), to a wall",
       {{"crates", 5, 0, 8, true, "crates in its way, 0.75 m apart"},
        {"speed", 2, 0, 100, false, "walking speed, m/s"}},
       filter_walk,
       [](const SceneParams& p) -> std::size_t { return 3 + p.count("crates"); },
       240},
  };
}

}  // namespace chainbench
