// SPDX-License-Identifier: MIT
// The 2014 engine's own test scenes (docs/algorithm-2014.md §7; conversions §1), from px/frame
// with y down to metres and seconds with y up: 50 px = 1 m (the engine's 50 px boxes are 1 m),
// 60 frames a second, so gravity 0.25 px/frame^2 becomes 18 m/s^2. Positions in the original
// are top-left corners.
#include "scenes/scene_library.h"

namespace chainbench {
namespace {

constexpr double kPxPerMetre = 50.0;
constexpr double kGravity = 0.25 * 60.0 * 60.0 / kPxPerMetre;  // 18 m/s^2

// A box given as the original's top-left corner and size in pixels.
std::size_t px_box(Scene& s, std::string name, BodyKind kind, double px, double py, double w,
                   double h, double mass = 1.0) {
  return build::box(s, std::move(name), kind,
                    {(px + 0.5 * w) / kPxPerMetre, -(py + 0.5 * h) / kPxPerMetre},
                    {0.5 * w / kPxPerMetre, 0.5 * h / kPxPerMetre}, mass);
}

Scene seeded(const char* name) {
  Scene s;
  s.name = name;
  s.gravity = {0.0, -kGravity};
  return s;
}

// 6eb2bf7: three 50 px boxes staggered 20 px, the lowest static.
Scene seed_stack(const SceneParams& p) {
  Scene s = seeded("seed_stack");
  const std::size_t top = px_box(s, "box0", BodyKind::kDynamic, 100, 200, 50, 50);
  const std::size_t middle = px_box(s, "box1", BodyKind::kDynamic, 120, 270, 50, 50);
  px_box(s, "base", BodyKind::kStatic, 140, 340, 50, 50);
  // Upright and frictionless, each box falls straight down onto the one below (they overlap by
  // 30 px): box1 rests on the base's top (y = -6.8 m), box0 on box1, neither moves sideways.
  const double fall = build::fallen(kGravity, p.get("dt"), p.count("steps"));
  s.expect.push_back(build::expect_center(
      middle, {2.9, std::max(-6.3, s.bodies[middle].center.y - fall)}, build::kVisible));
  s.expect.push_back(build::expect_center(top, {2.5, std::max(-5.3, s.bodies[top].center.y - fall)},
                                          build::kVisible));
  return s;
}

// 4f512fa: a platform rising at 1 px/frame under a static ceiling, with the 20 x 40 px player
// falling onto it. The original's massless, gravity-free box becomes 1 kg with gravity off (a
// dynamic body here needs mass); it stands apart and is never touched.
Scene seed_squeeze(const SceneParams& p) {
  Scene s = seeded("seed_squeeze");
  px_box(s, "player", BodyKind::kDynamic, 100, 100, 20, 40);
  const std::size_t block = px_box(s, "block", BodyKind::kDynamic, 300, 100, 50, 50);
  s.bodies[block].gravity_scale = 0.0;
  px_box(s, "ceiling", BodyKind::kStatic, 100, -100, 50, 50);
  const std::size_t platform = px_box(s, "platform", BodyKind::kKinematic, 100, 200, 50, 50);
  s.bodies[platform].velocity = {0.0, 60.0 / kPxPerMetre};  // 1 px/frame up
  // The untouched block stays put. The player lands on the platform and rides it straight up,
  // keeping its x, until the platform's top comes within its height of the ceiling at 3.5 s;
  // after that the platform ends inside the ceiling and no place is right for it.
  s.expect.push_back(build::expect_moved(block, {0.0, 0.0}, build::kVisible));
  Expectation rides = build::expect_bounds(0, 2.2 - build::kVisible * 0.4, std::nullopt,
                                           2.2 + build::kVisible * 0.4, std::nullopt);
  rides.from_step = 0;
  rides.to_step = std::min(200, p.count("steps"));
  s.expect.push_back(rides);
  // Squeezed to nothing, the 0.8 m player overlaps one of them by up to half its height.
  s.penetration_tolerance = 0.4 + build::kVisible * 0.4;
  return s;
}

// 1a6b023: a row of 10 boxes at y = 100 px and a second row at y = 0, shifted 10 px, falling onto
// it; 60 px pitch (from 71f99ca), starting at x = 30 px so that both rows fit the room. The tile
// level around them becomes a floor at its bottom row
// (the 20 x 14 map of 32 px tiles: top face at 416 px) and walls at its sides.
Scene seed_falling_row(const SceneParams& p) {
  Scene s = seeded("seed_falling_row");
  px_box(s, "floor", BodyKind::kStatic, 0, 416, 640, 32);
  px_box(s, "wall_left", BodyKind::kStatic, -32, 0, 32, 448);
  px_box(s, "wall_right", BodyKind::kStatic, 640, 0, 32, 448);
  // Each row falls straight down: the low row onto the floor (top at y = -8.32 m), each high box
  // onto the low box it overlaps by 40 px (its right edge only touches the next low box).
  const double fall = build::fallen(kGravity, p.get("dt"), p.count("steps"));
  auto lands_at = [&](std::size_t b, double rest) {
    const Vec2d c = s.bodies[b].center;
    s.expect.push_back(build::expect_center(b, {c.x, std::max(rest, c.y - fall)}, build::kVisible));
  };
  for (int i = 0; i < 10; ++i)
    lands_at(px_box(s, build::label("low", i), BodyKind::kDynamic, 30 + 60 * i, 100, 50, 50),
             -7.82);
  for (int i = 0; i < 10; ++i)
    lands_at(px_box(s, build::label("high", i), BodyKind::kDynamic, 40 + 60 * i, 0, 50, 50), -6.82);
  return s;
}

}  // namespace

std::vector<SceneRecipe> seed2014_scenes() {
  return {
      {"seed_stack",
       "seed2014",
       "2014 engine, 6eb2bf7: two boxes falling onto a static one, staggered",
       {},
       seed_stack,
       [](const SceneParams&) { return std::size_t{3}; },
       120},
      {"seed_squeeze",
       "seed2014",
       "2014 engine, 4f512fa: the player carried up into a ceiling by a rising platform",
       {},
       seed_squeeze,
       [](const SceneParams&) { return std::size_t{4}; },
       300},
      {"seed_falling_row",
       "seed2014",
       "2014 engine, 1a6b023: a row of 10 boxes falling onto another, in a tile room",
       {},
       seed_falling_row,
       [](const SceneParams&) { return std::size_t{23}; },
       180},
  };
}

}  // namespace chainbench
