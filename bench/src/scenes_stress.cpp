// Stress scenes: fast bodies, deep overlaps and squeezes, for `chainbench stress`.
#include "portable_random.h"
#include "scene_library.h"

#include <algorithm>
#include <cmath>

namespace chainbench {
namespace {

using build::box;
using build::ground;

// A 0.2 m projectile fired from 3 m away at the middle of a stack of five unit boxes, with no
// gravity on the projectile, at `speed`. Without continuous collision a body crosses a box in one
// step above about (box + projectile) / dt = 66 m/s: tunnelling, which stress reports. A static
// block 6 m behind the stack, 40 m deep and reaching 20 m below the floor, catches what gets
// through: its back face is the nearest exit for anything that enters below about 1,300 m/s, so
// the projectile stays in the scene and the verdict is about the solver.
Scene projectile(const SceneParams& p) {
  Scene s;
  s.name = "projectile";
  ground(s, 9.75, 0.0, -3.75);  // from x = -13.5 to the catcher's face at x = 6
  for (int i = 0; i < 5; ++i)
    box(s, build::label("box", i), BodyKind::kDynamic, {0.0, 0.5 + i}, {0.5, 0.5});
  box(s, "catcher", BodyKind::kStatic, {26.0, 5.0}, {20.0, 25.0});
  const std::size_t shot =
      box(s, "projectile", BodyKind::kDynamic, {-3.5, 2.5}, {0.1, 0.1}, p.get("mass"));
  s.bodies[shot].velocity = {p.get("speed"), 0.0};
  s.bodies[shot].gravity_scale = 0.0;
  return s;
}

// n boxes dropped at random places inside a narrow container, every one overlapping others.
Scene overlapping_pile(const SceneParams& p) {
  Scene s;
  s.name = "overlapping_pile";
  const int n = p.count("n");
  PortableRandom rng(static_cast<std::uint64_t>(p.count("seed")) * 104729u + 3u);
  const double width = std::max(6.0, std::sqrt(static_cast<double>(n)));
  const double height = 0.5 * static_cast<double>(n) / width;  // half the room the boxes need
  ground(s, 0.5 * width + 2.0);
  const double wall = 4.0 * height + 10.0;
  box(s, "wall_left", BodyKind::kStatic, {-0.5 * width - 0.5, 0.5 * wall}, {0.5, 0.5 * wall});
  box(s, "wall_right", BodyKind::kStatic, {0.5 * width + 0.5, 0.5 * wall}, {0.5, 0.5 * wall});
  for (int i = 0; i < n; ++i) {
    const double h = rng.uniform(0.3, 0.5);
    box(s, build::label("box", i), BodyKind::kDynamic,
        {rng.uniform(-0.5 * width + h, 0.5 * width - h), rng.uniform(h, h + height)}, {h, h},
        4.0 * h * h);
  }
  return s;
}

// A unit box between a floor and a ceiling `gap` metres apart (less than its height).
Scene static_squeeze(const SceneParams& p) {
  Scene s;
  s.name = "static_squeeze";
  ground(s, 5.0);
  const double gap = p.get("gap");
  box(s, "ceiling", BodyKind::kStatic, {0.0, gap + 1.0}, {5.0, 1.0});
  box(s, "box", BodyKind::kDynamic, {0.0, 0.5 * gap}, {0.5, 0.5});
  return s;
}

// A kinematic lift rising at `speed` under a unit box, towards a static ceiling.
Scene lift_squeeze(const SceneParams& p) {
  Scene s;
  s.name = "lift_squeeze";
  box(s, "ceiling", BodyKind::kStatic, {0.0, 4.0}, {3.0, 0.5});
  const std::size_t lift = box(s, "lift", BodyKind::kKinematic, {0.0, 0.0}, {1.5, 0.5});
  s.bodies[lift].velocity = {0.0, p.get("speed")};
  box(s, "rider", BodyKind::kDynamic, {0.0, 1.0}, {0.5, 0.5});
  return s;
}

// A row of n touching unit boxes between two kinematic walls closing in at `speed` each, top-down.
Scene converging_walls(const SceneParams& p) {
  Scene s;
  s.name = "converging_walls";
  s.gravity = {0.0, 0.0};
  const int n = p.count("n");
  const double half_row = 0.5 * n;
  const std::size_t left =
      box(s, "wall_left", BodyKind::kKinematic, {-half_row - 0.5, 0.0}, {0.5, 2.0});
  const std::size_t right =
      box(s, "wall_right", BodyKind::kKinematic, {half_row + 0.5, 0.0}, {0.5, 2.0});
  s.bodies[left].velocity = {p.get("speed"), 0.0};
  s.bodies[right].velocity = {-p.get("speed"), 0.0};
  for (int i = 0; i < n; ++i)
    box(s, build::label("box", i), BodyKind::kDynamic, {-half_row + 0.5 + i, 0.0}, {0.5, 0.5});
  return s;
}

}  // namespace

std::vector<SceneRecipe> stress_scenes() {
  return {
      {"projectile",
       "stress",
       "a 0.2 m projectile fired into a stack of five boxes (tunnelling above ~66 m/s)",
       {{"speed", 50, 0, 10000, false, "m/s"}, {"mass", 1, 1e-6, 1e9, false, "kg"}},
       projectile,
       [](const SceneParams&) { return std::size_t{8}; },
       120},
      {"overlapping_pile",
       "stress",
       "n boxes created at random inside each other in a narrow container",
       {{"n", 500, 1, 1000000, true, "boxes"}, {"seed", 1, 0, 2147483647, true, "layout seed"}},
       overlapping_pile,
       [](const SceneParams& p) { return static_cast<std::size_t>(p.count("n")) + 3; },
       300},
      {"static_squeeze",
       "stress",
       "a unit box between a floor and a ceiling closer than its height",
       {{"gap", 0.8, 0.01, 0.999, false, "floor to ceiling, m"}},
       static_squeeze,
       [](const SceneParams&) { return std::size_t{3}; },
       120},
      {"lift_squeeze",
       "stress",
       "a kinematic lift carrying a box up into a static ceiling",
       {{"speed", 1, 0, 1000, false, "lift speed, m/s"}},
       lift_squeeze,
       [](const SceneParams&) { return std::size_t{3}; },
       240},
      {"converging_walls",
       "stress",
       "top-down: a row of n boxes between two kinematic walls closing in",
       {{"n", 10, 1, 100000, true, "boxes"},
        {"speed", 0.5, 0, 1000, false, "speed of each wall, m/s"}},
       converging_walls,
       [](const SceneParams& p) { return static_cast<std::size_t>(p.count("n")) + 2; },
       120},
  };
}

}  // namespace chainbench
