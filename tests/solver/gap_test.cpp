// SPDX-License-Identifier: MIT
// A box crossing a gap between two grounds whose tops are level (a platformer's one-tile gap).
// Physically: a box wider than the gap always has one ground under it, so it crosses without
// losing height, at its own speed; a box narrower than the gap by more than two steps' travel is
// unsupported for a whole step and more, falls, and meets the far ground's side. In between (a
// gap wider than the box by less than two steps' travel) a step cannot tell a box that sank for
// part of a step from one that fell: either answer is allowed (entry_face.h). Steps from 1/240 s
// to 1 s (sub-steps and sweeps take the same face rule as push-out). Modern variant,
// frictionless, gravity (0, -10).
#include "world_helpers.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace chain::testing {
namespace {

struct Crossing {
  double edge;       // box edge, m
  double gap;        // between the grounds, m
  double speed;      // m/s, along +x (times `direction`)
  double dt;         // s
  double phase;      // where the leading edge starts, in steps' travel short of the near edge
  double direction;  // +1 rightwards, -1 the mirror image
  bool driven;       // a drive holds the x speed (a character), else a free slide
};

std::string name(const Crossing& c) {
  return "edge " + std::to_string(c.edge) + " gap " + std::to_string(c.gap) + " speed " +
         std::to_string(c.speed) + " dt " + std::to_string(c.dt) + " phase " +
         std::to_string(c.phase) + (c.direction < 0 ? " leftwards" : " rightwards") +
         (c.driven ? " driven" : " free");
}

struct Outcome {
  double x, y;      // where the box ends, m (mirrored back to rightwards)
  double lowest;    // the lowest y it had after any step
  int dipped;       // steps after which it was below its resting height by more than 1e-9 m
  double expect_x;  // where it would be had nothing slowed it
  int steps;
};

// Grounds [-2 r, 0] and [gap, gap + 2 r], r = 6 m + 5 steps' travel, tops at y = 0, 1 km deep;
// the box starts resting on the near ground with its leading edge (phase + 3) steps' travel short
// of the edge and runs until its trailing edge would be two steps past the far edge.
Outcome cross(const Crossing& c) {
  World w(world_def(Variant::kModern, VelocityRule::kZero));
  const double d = c.direction;
  const double travel = c.speed * c.dt;
  const double reach = 6.0 + 5.0 * travel;  // each ground's half length: past where the box goes
  w.create_body(static_box(d * -reach, -500.0, reach, 500.0));
  w.create_body(static_box(d * (c.gap + reach), -500.0, reach, 500.0));
  const double half = 0.5 * c.edge;
  const double x0 = -(c.phase + 3.0) * travel - half;
  BodyDef def = dynamic_box(d * x0, half, half, 1.0);
  def.velocity = {d * c.speed, 0.0};
  const BodyId box = w.create_body(def);
  if (c.driven) w.set_drive(box, {d * c.speed, 0.0}, DriveAxes::kX);
  const int steps = static_cast<int>(std::ceil((c.gap + c.edge) / travel - c.phase)) + 5;
  Outcome o{0.0, 0.0, half, 0, 0.0, steps};
  double x = x0;
  for (int s = 0; s < steps; ++s) {
    w.step(c.dt);
    x += travel;
    const double y = w.position(box).y;
    o.lowest = std::min(o.lowest, y);
    if (y < half - 1e-9) ++o.dipped;
  }
  o.x = d * w.position(box).x;
  o.y = w.position(box).y;
  o.expect_x = x;
  return o;
}

std::vector<Crossing> crossings(bool narrow) {
  std::vector<Crossing> all;
  for (const double edge : {0.25, 1.0, 2.0})
    for (const double speed : {1.0, 2.0, 8.0, 30.0})
      for (const double dt : {1.0 / 240.0, 1.0 / 60.0, 1.0 / 30.0, 0.1, 1.0})
        for (const double phase : {0.0, 0.25, 0.5, 0.75})
          for (const double direction : {1.0, -1.0})
            for (const bool driven : {false, true}) {
              if (narrow) {
                for (const double share : {0.3, 0.9, 0.95, 0.99, 1.0})
                  all.push_back({edge, share * edge, speed, dt, phase, direction, driven});
              } else {
                const double gap = edge + 2.0 * speed * dt + 0.05 * edge;
                all.push_back({edge, gap, speed, dt, phase, direction, driven});
              }
            }
  return all;
}

// Issue 23: a 1 m box driven at 2 m/s over a 1 m gap ended in the pit, and a free 1 m box
// sliding at 8 m/s over a 0.9 m gap stopped dead against the far ground's side: the step's
// gravity sink made the far top count as crossed at the step's start, so the box was judged to
// have come in through the side. Analytic: from x = -2.5 (leading edge at -2), 180 steps at
// 2 m/s end at x = 3.5; 60 steps at 8 m/s at x = 5.5; both resting at y = 0.5.
TEST(Gap, TheIssuesTwoBoxesCross) {
  for (const bool driven : {true, false}) {
    const double speed = driven ? 2.0 : 8.0, gap = driven ? 1.0 : 0.9;
    const int steps = driven ? 180 : 60;
    World w(world_def(Variant::kModern, VelocityRule::kZero));
    w.create_body(static_box(-5.0, -0.5, 5.0, 0.5));
    w.create_body(static_box(gap + 5.0, -0.5, 5.0, 0.5));
    BodyDef def = dynamic_box(-2.5, 0.5, 0.5, 1.0);
    def.velocity = {speed, 0.0};
    const BodyId box = w.create_body(def);
    if (driven) w.set_drive(box, {speed, 0.0}, DriveAxes::kX);
    for (int s = 0; s < steps; ++s)
      w.step(1.0 / 60.0);
    EXPECT_NEAR(w.position(box).x, -2.5 + speed * steps / 60.0, 1e-9) << driven;
    EXPECT_NEAR(w.position(box).y, 0.5, 1e-9) << driven;
  }
}

// Every box wider than the gap crosses: it ends where its speed takes it, at its resting height,
// and dips below that height after one step at most (the step it ends exactly over both corners,
// by that step's gravity sink g dt^2, before the far ground takes it).
TEST(Gap, EveryBoxWiderThanTheGapCrossesAtItsOwnSpeed) {
  int checked = 0;
  for (const Crossing& c : crossings(true)) {
    const Outcome o = cross(c);
    const double half = 0.5 * c.edge;
    EXPECT_NEAR(o.x, o.expect_x, 1e-9 * o.steps) << name(c);
    EXPECT_NEAR(o.y, half, 1e-9) << name(c);
    EXPECT_LE(o.dipped, 1) << name(c);
    EXPECT_GE(o.lowest, half - 10.0 * c.dt * c.dt - 1e-9) << name(c);
    ++checked;
  }
  EXPECT_EQ(checked, 3 * 4 * 5 * 4 * 2 * 2 * 5);
}

// A box narrower than the gap by more than two steps' travel falls in: it never gets past the far
// ground's side, and ends more than 1 mm below its resting height (it falls for five steps and
// more: at least 2 mm at 240 Hz).
TEST(Gap, ABoxNarrowerThanTheGapByTwoStepsTravelFallsIn) {
  for (const Crossing& c : crossings(false)) {
    const Outcome o = cross(c);
    EXPECT_LE(o.x, c.gap - 0.5 * c.edge + 1e-9) << name(c);
    EXPECT_LT(o.y, 0.5 * c.edge - 1e-3) << name(c);
  }
}

}  // namespace
}  // namespace chain::testing
