// SPDX-License-Identifier: MIT
// spawn_rain: bodies that come and go, in the spirit of Box2D's own rain benchmark. Every
// `period` steps a wave of boxes enters the world over a floor of static tiles, and once `waves`
// waves are in it the oldest leaves as the next enters, so the world holds about
// waves x cols x height boxes from then on and every engine pays for a wave's creation and a
// wave's removal each `period` steps, as a game pays for its projectiles and debris.
//
// The right answer is exact. The floor has waves x cols slots, one tile each, 1.5 m apart; wave w
// takes slot group w mod waves, which the wave before it in that group has just left (removals
// come before additions in a step). In each slot a wave is a column of `height` unit boxes,
// `gap` apart, whose lowest is `drop` above the floor: they fall together, and each stops on the
// floor or on the box under it, so box j of a slot rests at y = 0.5 + j. Nothing moves them
// sideways (upright, frictionless, inelastic, and the slots 0.5 m apart), so x never changes.
// Only the step of a landing may take a box deeper than 5 cm: by its speed times dt.
#include "scenes/scene_library.h"

#include <algorithm>
#include <cmath>

namespace chainbench {
namespace {

constexpr double kPitch = 1.5;  // m between slot centres: a unit box and 0.5 m of air
constexpr double kTolerance = build::kVisible;
constexpr double kG = 10.0;

struct Plan {
  int cols = 0, height = 0, waves = 0, period = 0, steps = 0;
  double drop = 0.0, gap = 0.0, dt = 0.0;
  // Waves that enter during the run: at steps 0, period, 2 period, ... before the last step.
  int entering() const { return (steps + period - 1) / period; }
  int slots() const { return waves * cols; }
  // Steps until the top box of a slot has come to rest: its fall of drop plus the gaps under it,
  // from rest, and ten steps for the blows to die down in engines that solve iteratively.
  int settle_steps() const {
    const double fall = drop + (height - 1) * gap;
    return static_cast<int>(std::ceil(std::sqrt(2.0 * fall / kG) / dt)) + 10;
  }
};

Plan plan_of(const SceneParams& p) {
  Plan plan;
  plan.cols = p.count("cols"), plan.height = p.count("height"), plan.waves = p.count("waves");
  plan.period = p.count("period"), plan.steps = p.count("steps");
  plan.drop = p.get("drop"), plan.gap = p.get("gap"), plan.dt = p.get("dt");
  return plan;
}

double slot_x(const Plan& plan, int slot) {
  return kPitch * (slot - 0.5 * (plan.slots() - 1));
}

Scene spawn_rain(const SceneParams& p) {
  const Plan plan = plan_of(p);
  Scene s;
  s.name = "spawn_rain";
  for (int t = 0; t < plan.slots(); ++t) {
    build::box(s, build::label("tile", t), BodyKind::kStatic, {slot_x(plan, t), -0.5},
               {0.5 * kPitch, 0.5});
  }
  const int settle = plan.settle_steps();
  for (int w = 0; w < plan.entering(); ++w) {
    const int from = w * plan.period, to = from + plan.waves * plan.period;
    const int group = w % plan.waves;
    for (int c = 0; c < plan.cols; ++c) {
      const double x = slot_x(plan, group * plan.cols + c);
      for (int j = 0; j < plan.height; ++j) {
        const double y0 = 0.5 + plan.drop + j * (1.0 + plan.gap), rest = 0.5 + j;
        const std::size_t b = build::box(s, build::label("w", w, c * plan.height + j),
                                         BodyKind::kDynamic, {x, y0}, {0.5, 0.5});
        s.bodies[b].from_step = from;
        s.bodies[b].to_step = to;
        const int last = std::min(to, plan.steps);  // the last state it is seen in
        // Straight down, never up, and never below its rest by more than the step in which it
        // lands can take it before a discrete engine answers the contact: its speed then, from
        // its fall of drop plus the gaps under it, times dt.
        const double impact = std::sqrt(2.0 * kG * (plan.drop + j * plan.gap)) * plan.dt;
        Expectation within = build::expect_bounds(b, x - kTolerance, rest - kTolerance - impact,
                                                  x + kTolerance, y0 + kTolerance);
        within.from_step = from, within.to_step = last;
        s.expect.push_back(within);
        // At rest where it belongs from the time it settled to the state it leaves in.
        if (last - from >= settle) {
          Expectation landed = build::expect_center(b, {x, rest}, kTolerance);
          landed.from_step = from + settle, landed.to_step = last;
          s.expect.push_back(landed);
        }
      }
    }
  }
  return s;
}

std::size_t spawn_rain_count(const SceneParams& p) {
  const Plan plan = plan_of(p);
  return static_cast<std::size_t>(plan.slots()) + static_cast<std::size_t>(plan.entering()) *
                                                      static_cast<std::size_t>(plan.cols) *
                                                      static_cast<std::size_t>(plan.height);
}

}  // namespace

SceneRecipe spawn_rain_recipe() {
  return {"spawn_rain",
          "moving",
          "waves of box columns entering over a tiled floor every period steps, the oldest "
          "leaving once `waves` are in: about waves x cols x height boxes at a time",
          {{"cols", 10, 1, 1000000, true, "slots each wave fills"},
           {"height", 3, 1, 1000, true, "boxes stacked in each slot"},
           {"waves", 6, 1, 100000, true, "waves in the world at once"},
           {"period", 10, 1, 1000000, true, "steps between waves"},
           {"drop", 1, 0.01, 1000, false, "height of a wave's lowest box above the floor, m"},
           {"gap", 0.25, 0.01, 100, false, "air between the boxes of a slot, m"}},
          spawn_rain,
          spawn_rain_count,
          120};
}

}  // namespace chainbench
