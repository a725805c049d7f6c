// SPDX-License-Identifier: MIT
// Large time steps (solver/src/substeps.h): a step whose gravity would sink some dynamic box past
// its half extent is split into sub-steps, so resting stacks hold and pushes do not tunnel at any
// dt up to 1 s; below that nothing changes. The step's report joins its sub-steps'.
#include "world_helpers.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace chain::testing {
namespace {

// Issue 23: a resting two-box stack collapsed at dt >= 0.35 s (the top box ended on the floor
// beside the lower one). Stacks of 2, 5 and 10 boxes of 0.25, 1 and 4 m, and a pyramid of base 5,
// rest where they were built, to rounding, after 3 s at every dt up to 1 s.
TEST(Substeps, RestingStacksHoldAtEveryTimeStepUpToOneSecond) {
  for (const double dt : {0.1, 0.2, 0.35, 0.5, 0.75, 1.0}) {
    for (const double edge : {0.25, 1.0, 4.0}) {
      for (const int n : {2, 5, 10, 0}) {  // 0: a pyramid of base 5
        World w(world_def(Variant::kModern, VelocityRule::kInelastic));
        add_floor(w);
        std::vector<BodyId> ids;
        std::vector<Vec2> built;
        auto add = [&](double x, double y) {
          ids.push_back(w.create_body(dynamic_box(x, y, 0.5 * edge)));
          built.push_back({x, y});
        };
        if (n > 0) {
          for (int i = 0; i < n; ++i)
            add(0.0, edge * (i + 0.5));
        } else {
          for (int row = 0; row < 5; ++row)
            for (int i = 0; i < 5 - row; ++i)
              add(edge * (i + 0.5 * row), edge * (row + 0.5));
        }
        const std::string what = "dt " + std::to_string(dt) + " edge " + std::to_string(edge) +
                                 " n " + std::to_string(n);
        for (int s = 0; s < static_cast<int>(std::round(3.0 / dt)); ++s)
          w.step(dt);
        for (std::size_t i = 0; i < ids.size(); ++i) {
          EXPECT_NEAR(w.position(ids[i]).x, built[i].x, 1e-9) << what << " box " << i;
          EXPECT_NEAR(w.position(ids[i]).y, built[i].y, 1e-9 * edge) << what << " box " << i;
        }
      }
    }
  }
}

// Sub-steps are taken only where a step's gravity sinks a box past its half extent, and then as
// few as keep each under it: n = ceil(dt sqrt(g / half)) for unit boxes in g = 10.
TEST(Substeps, AreTakenOnlyWhereGravitySinksABoxPastItsHalfExtent) {
  for (const double dt : {1.0 / 60.0, 0.1, 0.2, 0.22, 0.23, 0.35, 1.0}) {
    World w(world_def(Variant::kModern, VelocityRule::kInelastic));
    add_floor(w);
    w.create_body(dynamic_box(0.0, 0.5));
    w.step(dt);
    const double want = std::max(1.0, std::ceil(dt * std::sqrt(10.0 / 0.5)));
    EXPECT_EQ(w.last_step_stats().substeps, static_cast<std::uint32_t>(want)) << dt;
  }
  // Without gravity, or with a body that gravity leaves alone, there is nothing to split.
  World flat(world_def(Variant::kModern, VelocityRule::kInelastic, {0.0, 0.0}));
  flat.create_body(dynamic_box(0.0, 0.5));
  flat.step(1.0);
  EXPECT_EQ(flat.last_step_stats().substeps, 1u);
  World weightless(world_def(Variant::kModern, VelocityRule::kInelastic));
  BodyDef d = dynamic_box(0.0, 0.5);
  d.gravity_scale = 0.0;
  const BodyId floating = weightless.create_body(d);
  weightless.step(1.0);
  EXPECT_EQ(weightless.last_step_stats().substeps, 1u);
  // The smallest box decides; once it is destroyed, the next step no longer splits.
  const BodyId tiny = weightless.create_body(dynamic_box(5.0, 0.5, 0.01));
  weightless.step(0.1);
  EXPECT_EQ(weightless.last_step_stats().substeps,
            static_cast<std::uint32_t>(std::ceil(0.1 * std::sqrt(10.0 / 0.01))));
  weightless.destroy_body(tiny);
  weightless.step(0.1);
  EXPECT_EQ(weightless.last_step_stats().substeps, 1u);
  EXPECT_TRUE(weightless.contains(floating));
  // 2014's variant is the faithful one: never split.
  World seed(world_def(Variant::kSeed2014, VelocityRule::kZero));
  seed.create_body(dynamic_box(0.0, 0.5));
  seed.step(1.0);
  EXPECT_EQ(seed.last_step_stats().substeps, 1u);
}

// A drive sets its velocity at the start of the step only: a driven 1 kg pusher against a 1 kg
// box on a frictionless floor shares its momentum once a step, as without sub-steps, so after
// one step of dt both have moved v dt / 2 and move at v / 2 (the inelastic rule), whatever the
// sub-steps; the next step's drive restores v.
TEST(Substeps, DrivesSetTheirVelocityOnceAStep) {
  for (const double dt : {0.05, 0.35, 1.0}) {
    World w(world_def(Variant::kModern, VelocityRule::kInelastic));
    add_floor(w);
    const BodyId pusher = w.create_body(dynamic_box(0.0, 0.5));
    const BodyId box = w.create_body(dynamic_box(1.0, 0.5));
    w.set_drive(pusher, {2.0, 0.0}, DriveAxes::kX);
    w.step(dt);
    EXPECT_NEAR(w.position(pusher).x, 0.5 * 2.0 * dt, 1e-9) << dt;
    EXPECT_NEAR(w.position(box).x, 1.0 + 0.5 * 2.0 * dt, 1e-9) << dt;
    EXPECT_NEAR(w.velocity(box).x, 1.0, 1e-9) << dt;
    EXPECT_NEAR(w.position(box).y, 0.5, 1e-9) << dt;
    w.step(dt);
    EXPECT_NEAR(w.velocity(pusher).x, w.velocity(box).x, 1e-9) << dt;
  }
}

// Pushes at large steps do not tunnel: a driven pusher shoving rows of 1 to 8 boxes, and a
// stack of 3, along the floor at 2 m/s never overlaps what it pushes, at every dt up to 1 s, and
// the boxes keep their order.
TEST(Substeps, PushesDoNotTunnelAtLargeSteps) {
  for (const double dt : {0.1, 0.35, 0.5, 1.0}) {
    for (const int n : {1, 3, 8, -3}) {  // -3: a stack of three, pushed by a pusher as tall
      World w(world_def(Variant::kModern, VelocityRule::kInelastic));
      const BodyId floor = add_floor(w, 200.0);
      std::vector<BodyId> ids = {floor};
      std::vector<Vec2> half = {{200.0, 1.0}};
      const double tall = n < 0 ? 3.0 : 1.0;
      BodyDef p = dynamic_box(0.0, 0.5 * tall);
      p.half_extents = {0.5, 0.5 * tall};
      const BodyId pusher = w.create_body(p);
      ids.push_back(pusher);
      half.push_back(p.half_extents);
      w.set_drive(pusher, {2.0, 0.0}, DriveAxes::kX);
      for (int i = 0; i < std::abs(n); ++i) {
        const double x = n < 0 ? 1.0 : 1.0 + i, y = n < 0 ? 0.5 + i : 0.5;
        ids.push_back(w.create_body(dynamic_box(x, y)));
        half.push_back({0.5, 0.5});
      }
      for (int s = 0; s < static_cast<int>(std::round(3.0 / dt)); ++s) {
        w.step(dt);
        ASSERT_LE(max_penetration(w, ids, half), 1e-9) << dt << " n " << n << " step " << s;
      }
      for (std::size_t i = 2; i < ids.size(); ++i)
        EXPECT_GE(w.position(ids[i]).x, w.position(pusher).x + 1.0 - 1e-9) << dt << " n " << n;
    }
  }
}

// The report joins the sub-steps': a box on the floor touches it below; a box a lift presses into
// a ceiling is reported crushed once, however many sub-steps pressed it.
TEST(Substeps, TheStepReportsItsSubStepsTogether) {
  World w(world_def(Variant::kModern, VelocityRule::kInelastic));
  add_floor(w);
  const BodyId resting = w.create_body(dynamic_box(-5.0, 0.5));
  w.create_body(static_box(5.0, 2.5, 2.0, 0.5));  // ceiling, bottom face at y = 2
  w.create_body(kinematic_box(5.0, 0.25, 2.0, 0.25, {0.0, 0.5}));
  const BodyId rider = w.create_body(dynamic_box(5.0, 1.0));
  for (int s = 0; s < 3; ++s) {
    w.step(0.5);
    ASSERT_EQ(w.last_step_stats().substeps, 3u);  // ceil(0.5 sqrt(10 / 0.5))
    EXPECT_NE(w.touching_flags(resting) & touching::kBottom, 0) << s;
  }
  int crushed = 0;
  for (const CrushEvent& e : w.crush_events())
    crushed += e.body == rider;
  EXPECT_EQ(crushed, 1);
  EXPECT_EQ(w.last_step_stats().crush_events, w.crush_events().size());
}

}  // namespace
}  // namespace chain::testing
