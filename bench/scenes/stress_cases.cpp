// SPDX-License-Identifier: MIT
// Stress scenes: fast bodies, deep overlaps and squeezes, for `chainbench stress`.
#include "scenes/portable_random.h"
#include "scenes/scene_library.h"

#include <algorithm>
#include <cmath>

namespace chainbench {
namespace {

using build::box;
using build::ground;

// A 0.2 m projectile fired from 3 m away at the middle of a stack of five unit boxes, with no
// gravity on the projectile, at `speed`. A static backstop 40 m deep stands flush against the
// stack's far side, so whatever the projectile's mass the stack cannot give way: the right answer
// is that the projectile stops against box2 and nothing else moves. Without continuous collision a
// body crosses a box in one step above about (box + projectile) / dt = 66 m/s.
Scene projectile(const SceneParams& p) {
  Scene s;
  s.name = "projectile";
  ground(s, 9.75, 0.0, -3.75);  // from x = -13.5 into the backstop
  for (int i = 0; i < 5; ++i)
    box(s, build::label("box", i), BodyKind::kDynamic, {0.0, 0.5 + i}, {0.5, 0.5});
  box(s, "backstop", BodyKind::kStatic, {20.5, 5.0}, {20.0, 25.0});
  const std::size_t shot =
      box(s, "projectile", BodyKind::kDynamic, {-3.5, 2.5}, {0.1, 0.1}, p.get("mass"));
  s.bodies[shot].velocity = {p.get("speed"), 0.0};
  s.bodies[shot].gravity_scale = 0.0;
  // Never past box2's near face (x = -0.5), and resting against it at the end (restitution 0),
  // unless the run ends before it gets there.
  const double stop = -0.5 - 0.1, slack = build::kVisible * 0.2;
  Expectation never_in =
      build::expect_bounds(shot, std::nullopt, std::nullopt, stop + slack, std::nullopt);
  never_in.from_step = 0;
  s.expect.push_back(never_in);
  const double flown = -3.5 + p.get("speed") * p.get("dt") * p.count("steps");
  s.expect.push_back(build::expect_center(shot, {std::min(stop, flown), 2.5}, slack));
  for (std::size_t i = 1; i <= 5; ++i)
    s.expect.push_back(build::expect_moved(i, {0.0, 0.0}, build::kVisible));
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
  // Where each box ends is not unique; that it ends inside the container, above the floor, and
  // apart from the others by the run's end is.
  const double slack = build::kVisible * 0.6;  // of the smallest box
  s.expect.push_back(build::expect_bounds(build::kEvery, -0.5 * width + 0.3 - slack, 0.3 - slack,
                                          0.5 * width - 0.3 + slack, std::nullopt));
  s.expect.push_back(build::expect_no_overlap(slack));
  return s;
}

// A unit box between a floor and a ceiling `gap` metres apart (less than its height).
Scene static_squeeze(const SceneParams& p) {
  Scene s;
  s.name = "static_squeeze";
  ground(s, 5.0);
  const double gap = p.get("gap");
  box(s, "ceiling", BodyKind::kStatic, {0.0, gap + 1.0}, {5.0, 1.0});
  const std::size_t b = box(s, "box", BodyKind::kDynamic, {0.0, 0.5 * gap}, {0.5, 0.5});
  build::expect_squeezed(s, b, 1, 0.0, gap, 1.0);
  return s;
}

// A kinematic lift rising at `speed` under a unit box, towards a static ceiling.
Scene lift_squeeze(const SceneParams& p) {
  Scene s;
  s.name = "lift_squeeze";
  box(s, "ceiling", BodyKind::kStatic, {0.0, 4.0}, {3.0, 0.5});
  const std::size_t lift = box(s, "lift", BodyKind::kKinematic, {0.0, 0.0}, {1.5, 0.5});
  s.bodies[lift].velocity = {0.0, p.get("speed")};
  const std::size_t rider = box(s, "rider", BodyKind::kDynamic, {0.0, 1.0}, {0.5, 0.5});
  // The lift's top ends at 0.5 + speed t; the ceiling's face is at 3.5.
  const double lift_top = 0.5 + p.get("speed") * p.get("dt") * p.count("steps");
  if (lift_top + 1.0 <= 3.5) {
    s.expect.push_back(build::expect_center(rider, {0.0, lift_top + 0.5}, build::kVisible));
  } else {
    build::expect_squeezed(s, rider, 1, lift_top, 3.5, 1.0);
  }
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
  // The walls take the row's length down by 2 speed t: no place is right, and the least
  // penetrating shares the squeeze among the n + 1 contacts. Every centre stays between the
  // walls' faces, and the row keeps to its line.
  const double closed =
      std::min(2.0 * p.get("speed") * p.get("dt") * p.count("steps"), static_cast<double>(n));
  const double face = half_row - 0.5 * closed;
  s.penetration_tolerance = closed / (n + 1) + build::kVisible;
  s.expect.push_back(
      build::expect_bounds(build::kEvery, -face, -build::kVisible, face, build::kVisible));
  return s;
}

}  // namespace

std::vector<SceneRecipe> stress_scenes() {
  return {
      {"projectile",
       "stress",
       "a 0.2 m projectile fired into a stack of five boxes backed by a wall: it must stop there",
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
       "a kinematic lift carrying a box up into a static ceiling (it ends half its height)",
       {{"speed", 1, 0, 1000, false, "lift speed, m/s"}},
       lift_squeeze,
       [](const SceneParams&) { return std::size_t{3}; },
       150},
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
