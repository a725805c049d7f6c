// SPDX-License-Identifier: MIT
// churn: the cost of bodies coming and going in a world that does not otherwise change. A wall of
// `cols` columns of `height` unit boxes rests on the ground (stack_wall's), and in every step
// `per_step` unit boxes enter high above it and leave after that one step, so every step but the
// first creates `per_step` bodies and destroys as many, as a game's projectiles and pickups do.
// With per_step=0 it is the same wall with nothing coming or going: the step it is compared with.
//
// The right answer is exact: the wall never moves, and a passing box only falls for its one step
// (its first state is where it enters; it leaves before the next is judged).
#include "scenes/scene_library.h"

namespace chainbench {
namespace {

// Boxes enter this far above the wall's top, side by side: they never meet the wall or each other.
constexpr double kAbove = 10.0;

Scene churn(const SceneParams& p) {
  Scene s;
  s.name = "churn";
  const int cols = p.count("cols"), height = p.count("height");
  const int per_step = p.count("per_step"), steps = p.count("steps");
  build::box(s, "ground", BodyKind::kStatic, {0.0, -0.5}, {0.5 * cols + 2.0, 0.5});
  for (int c = 0; c < cols; ++c) {
    for (int r = 0; r < height; ++r) {
      build::box(s, build::label("b", c, r), BodyKind::kDynamic, {c - 0.5 * (cols - 1), 0.5 + r},
                 {0.5, 0.5});
    }
  }
  build::expect_at_rest_where_built(s);
  // Step k's boxes take part in step k only; within a step they stand 2 m apart in rows along the
  // wall, so none meets another.
  const int across = (cols + 1) / 2;
  for (int k = 0; k < steps; ++k) {
    for (int j = 0; j < per_step; ++j) {
      const double x = 2.0 * (j % across) - 0.5 * (cols - 1);
      const double y = height + kAbove + 2.0 * (j / across);
      const std::size_t b =
          build::box(s, build::label("pass", k, j), BodyKind::kDynamic, {x, y}, {0.5, 0.5});
      s.bodies[b].from_step = k;
      s.bodies[b].to_step = k + 1;
    }
  }
  return s;
}

std::size_t churn_count(const SceneParams& p) {
  return static_cast<std::size_t>(p.count("cols")) * static_cast<std::size_t>(p.count("height")) +
         1 +
         static_cast<std::size_t>(p.count("per_step")) * static_cast<std::size_t>(p.count("steps"));
}

}  // namespace

SceneRecipe churn_recipe() {
  return {"churn",
          "moving",
          "a resting wall of cols columns while per_step boxes a step enter above it and leave the "
          "next: what bodies coming and going cost",
          {{"cols", 100, 1, 1000000, true, "columns of the wall"},
           {"height", 10, 1, 1000, true, "boxes in each column"},
           {"per_step", 1, 0, 1000, true, "boxes created and destroyed each step"}},
          churn,
          churn_count,
          120};
}

}  // namespace chainbench
