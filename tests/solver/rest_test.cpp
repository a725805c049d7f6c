// SPDX-License-Identifier: MIT
// WorldDef::skip_rest: a world that skips the steps it would rebuild and one that solves every
// step, stepped in lockstep through settling, every kind of change the API makes and a change of
// dt, agree to the bit after every step (centres, velocities, touching flags); the skipping one
// skips once two steps in a row left it still, and never the step after a change.
#include "world_helpers.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <functional>
#include <vector>

namespace chain {
namespace {

using testing::add_floor;
using testing::bits;
using testing::dynamic_box;
using testing::kinematic_box;

class Lockstep {
 public:
  Lockstep() {
    WorldDef solve_def;
    solve_def.skip_rest = false;
    solve_ = World(solve_def);
    for (World* w : {&skip_, &solve_}) {
      add_floor(*w);
      for (int k = 0; k < 5; ++k)
        top_ = w->create_body(dynamic_box(0.0, 0.5 + k, 0.5));
      lift_ = w->create_body(kinematic_box(4.0, 0.25, 1.0, 0.25, {0.0, 0.0}));
    }
  }
  // Steps both; returns whether the skipping world skipped, after checking they agree.
  bool step(double dt = 1.0 / 60.0) {
    skip_.step(dt);
    solve_.step(dt);
    EXPECT_EQ(solve_.last_step_stats().skipped, 0u);
    const std::size_t n = skip_.body_count();
    EXPECT_EQ(n, solve_.body_count());
    std::vector<BodyId> ids_a(n), ids_b(n);
    std::vector<Vec2> pa(n), pb(n), va(n), vb(n);
    skip_.read_all(ids_a, pa, va);
    solve_.read_all(ids_b, pb, vb);
    for (std::size_t k = 0; k < n; ++k) {
      EXPECT_EQ(ids_a[k].value, ids_b[k].value);
      EXPECT_EQ(bits(pa[k].x), bits(pb[k].x)) << "body " << ids_a[k].value;
      EXPECT_EQ(bits(pa[k].y), bits(pb[k].y)) << "body " << ids_a[k].value;
      EXPECT_EQ(bits(va[k].x), bits(vb[k].x)) << "body " << ids_a[k].value;
      EXPECT_EQ(bits(va[k].y), bits(vb[k].y)) << "body " << ids_a[k].value;
      EXPECT_EQ(skip_.touching_flags(ids_a[k]), solve_.touching_flags(ids_b[k]));
    }
    EXPECT_EQ(skip_.crush_events().size(), solve_.crush_events().size());
    return skip_.last_step_stats().skipped == 1;
  }
  // Steps `count` times; returns how many of them were skipped.
  int steps(int count, double dt = 1.0 / 60.0) {
    int skipped = 0;
    for (int k = 0; k < count; ++k)
      skipped += step(dt) ? 1 : 0;
    return skipped;
  }
  // Applies `change` to both worlds, then checks the next step is solved.
  void change(const std::function<void(World&)>& fn) {
    fn(skip_);
    fn(solve_);
    EXPECT_FALSE(step()) << "the step after a change was skipped";
  }
  BodyId top() const { return top_; }
  BodyId lift() const { return lift_; }

 private:
  World skip_, solve_;
  BodyId top_, lift_;
};

TEST(SkipRest, AStackAtRestSkipsItsStepsAndEveryChangeWakesIt) {
  Lockstep w;
  // Built touching: the first two steps are solved, every later one skipped.
  EXPECT_FALSE(w.step());
  EXPECT_FALSE(w.step());
  EXPECT_EQ(w.steps(30), 30);

  // The same velocity again still counts as a change; a jump lands and rests again.
  w.change([&](World& x) { x.set_velocity(w.top(), {0.0, 0.0}); });
  EXPECT_EQ(w.steps(20), 19);
  // Up and back down in 2 v / g = 0.6 s (36 steps); then the check may wait up to 31 steps
  // (rest.h) and takes two still steps.
  w.change([&](World& x) { x.set_velocity(w.top(), {0.0, 3.0}); });
  EXPECT_GE(w.steps(120), 120 - 38 - 31 - 2);
  // Drives, at zero and moving, and their end.
  w.change([&](World& x) { x.set_drive(w.lift(), {0.0, 0.0}); });
  EXPECT_GT(w.steps(10), 5);
  w.change([&](World& x) { x.set_drive(w.lift(), {0.5, 0.0}); });
  EXPECT_EQ(w.steps(20), 0);  // the lift moves
  w.change([&](World& x) { x.clear_drive(w.lift()); });
  // Cleared, the lift keeps the drive's velocity (a kinematic body keeps its own): set it still.
  // After 20 steps of checks that found it moving, the check waits up to 31 steps (rest.h).
  w.change([&](World& x) { x.set_velocity(w.lift(), {0.0, 0.0}); });
  EXPECT_GE(w.steps(60), 60 - 1 - 31 - 2);
  // A body created above the stack falls onto it; then it goes again.
  BodyId dropped;
  w.change([&](World& x) { dropped = x.create_body(dynamic_box(0.0, 9.0, 0.5)); });
  EXPECT_GT(w.steps(120), 40);
  w.change([&](World& x) { x.destroy_body(dropped); });
  EXPECT_GT(w.steps(10), 5);
  // A new dt: its first step is solved; it left the world still from a start at velocity +0, so
  // it was a fixed point for that dt, and the next steps of it are skipped. So back.
  EXPECT_FALSE(w.step(1.0 / 30.0));
  EXPECT_EQ(w.steps(5, 1.0 / 30.0), 5);
  EXPECT_FALSE(w.step());
  EXPECT_EQ(w.steps(5), 5);
}

// A world that moves never skips: a body sliding at a steady speed on a frictionless floor comes
// out of every step somewhere else.
TEST(SkipRest, AMovingWorldIsSolvedEveryStep) {
  World w;
  add_floor(w);
  BodyDef slider = dynamic_box(0.0, 0.5, 0.5);
  slider.velocity = {1.0, 0.0};
  w.create_body(slider);
  for (int k = 0; k < 60; ++k) {
    w.step(1.0 / 60.0);
    EXPECT_EQ(w.last_step_stats().skipped, 0u) << "step " << k;
  }
}

}  // namespace
}  // namespace chain
