// SPDX-License-Identifier: MIT
// Pushing scenes: a driven body shoving others, top-down and side-on, and a squeeze.
#include "scenes/scene_library.h"

#include <algorithm>

namespace chainbench {
namespace {

using build::box;
using build::ground;

// Top-down (no gravity): a pusher at x = 0 driven along +x into n touching unit boxes.
Scene push_row_common(const SceneParams& p, const char* name) {
  Scene s;
  s.name = name;
  s.gravity = {0.0, 0.0};
  const std::size_t pusher =
      box(s, "pusher", BodyKind::kDynamic, {0.0, 0.0}, {0.5, 0.5}, p.get("pusher_mass"));
  for (int i = 1; i <= p.count("n"); ++i)
    box(s, build::label("box", i), BodyKind::kDynamic, {1.0 * i, 0.0}, {0.5, 0.5});
  s.drivers.push_back({pusher, {p.get("speed"), 0.0}, 0, limits::kMaxSteps});
  return s;
}

// The pusher and the row move as one, a little behind the drive while the row takes up speed
// (driven_push_distance).
void expect_driven_row(Scene& s, const SceneParams& p, double row_mass) {
  const double d = build::driven_push_distance(p.get("speed"), p.get("pusher_mass"), row_mass,
                                               p.get("dt"), p.count("steps"));
  s.expect.push_back(build::expect_moved(build::kEvery, {d, 0.0}, build::kVisible));
}

Scene push_row(const SceneParams& p) {
  Scene s = push_row_common(p, "push_row");
  expect_driven_row(s, p, p.count("n"));
  return s;
}

Scene push_into_wall(const SceneParams& p) {
  Scene s = push_row_common(p, "push_into_wall");
  box(s, "wall", BodyKind::kStatic, {p.count("n") + 1.0, 0.0}, {0.5, 2.0});
  build::expect_at_rest_where_built(s);  // rigid boxes against a wall: however hard the push
  return s;
}

// Side-on: a pusher as tall as a stack of unit boxes shoves it along the floor. The floor
// contacts must not be resolved sideways (the chaining axis).
Scene push_stack(const SceneParams& p) {
  Scene s;
  s.name = "push_stack";
  ground(s, 30.0);
  const int height = p.count("height");
  const std::size_t pusher = box(s, "pusher", BodyKind::kDynamic, {0.0, 0.5 * height},
                                 {0.5, 0.5 * height}, p.get("pusher_mass"));
  for (int i = 0; i < height; ++i)
    box(s, build::label("box", i), BodyKind::kDynamic, {1.0, 0.5 + i}, {0.5, 0.5});
  s.drivers.push_back({pusher, {p.get("speed"), 0.0}, 0, limits::kMaxSteps});
  // The pusher is as tall as the stack: every box is pushed along with it, none rides up or falls
  // behind. On a frictionless floor they move as the momentum-sharing push says. With friction mu
  // how far depends on how an engine lets friction act on a velocity set at the start of a step:
  // at most it takes mu g dt (1 + stack / pusher) of it each step (the friction of everything
  // the pusher shoves), so each body ends between that lag and none.
  const double mu = p.get("friction");
  if (mu <= 0.0) {
    expect_driven_row(s, p, height);
    return s;
  }
  const double dt = p.get("dt");
  const int steps = p.count("steps");
  const double d =
      build::driven_push_distance(p.get("speed"), p.get("pusher_mass"), height, dt, steps);
  const double lag =
      std::min(d, steps * mu * 10.0 * dt * dt * (1.0 + height / p.get("pusher_mass")));
  for (std::size_t b = pusher; b < s.bodies.size(); ++b) {
    const Vec2d c = s.bodies[b].center;
    s.expect.push_back(build::expect_bounds(b, c.x + d - lag - build::kVisible,
                                            c.y - build::kVisible, c.x + d + build::kVisible,
                                            c.y + build::kVisible));
  }
  return s;
}

// A unit box on the floor and a kinematic lift coming down on it.
Scene squeeze(const SceneParams& p) {
  Scene s;
  s.name = "squeeze";
  ground(s, 10.0);
  box(s, "box", BodyKind::kDynamic, {0.0, 0.5}, {0.5, 0.5});
  const std::size_t lift =
      box(s, "lift", BodyKind::kKinematic, {0.0, 1.5 + p.get("gap")}, {1.5, 0.5});
  s.bodies[lift].velocity = {0.0, -p.get("speed")};
  // The lift's face ends `gap - speed t` above the box's top; once lower, the box is squeezed.
  const double lift_bottom = 1.0 + p.get("gap") - p.get("speed") * p.get("dt") * p.count("steps");
  if (lift_bottom >= 1.0) {
    build::expect_at_rest_where_built(s);
  } else {
    build::expect_squeezed(s, 1, 1, 0.0, lift_bottom, 1.0);
  }
  return s;
}

std::size_t row_count(const SceneParams& p) {
  return static_cast<std::size_t>(p.count("n")) + 1;
}
std::size_t row_and_wall_count(const SceneParams& p) {
  return row_count(p) + 1;
}

}  // namespace

std::vector<SceneRecipe> pushing_scenes() {
  const std::vector<SceneParam> row = {
      {"n", 10, 1, 1000000, true, "boxes in the row"},
      {"speed", 2, 0, 1000, false, "pusher speed, m/s"},
      {"pusher_mass", 1, 1e-6, 1e9, false, "kg (the boxes are 1 kg)"}};
  return {
      {"push_row", "pushing", "top-down: a driven pusher against a row of n touching boxes", row,
       push_row, row_count, 120},
      {"push_into_wall", "pushing", "push_row with a static wall after the row: nothing may move",
       row, push_into_wall, row_and_wall_count, 120},
      {"push_stack",
       "pushing",
       "side-on: a pusher shoving a stack along the floor (the chaining-axis case)",
       {{"height", 2, 1, 1000, true, "boxes in the stack (and pusher height, m)"},
        {"speed", 1, 0, 1000, false, "pusher speed, m/s"},
        {"pusher_mass", 1, 1e-6, 1e9, false, "kg"}},
       push_stack,
       [](const SceneParams& p) { return static_cast<std::size_t>(p.count("height")) + 2; },
       120},
      {"squeeze",
       "pushing",
       "a box between the floor and a descending kinematic lift (it ends half its height)",
       {{"speed", 0.5, 0, 1000, false, "lift speed, m/s"},
        {"gap", 0.5, 0, 1000, false, "lift start above the box, m"}},
       squeeze,
       [](const SceneParams&) { return std::size_t{3}; },
       120},
  };
}

}  // namespace chainbench
