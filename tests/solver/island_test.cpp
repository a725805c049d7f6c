// SPDX-License-Identifier: MIT
// Resting islands left out of a step (islands.h) change no result. Each world below is stepped in
// lockstep beside a twin that solves every body every step (WorldDef::skip_rest off), and after
// every step the two agree to the bit: centres, velocities, touching flags and crush events.
// Every world is run on 1, 2, 3 and 8 threads, and once more with no island woken ahead of a
// body that reaches it, so that every meeting is found after its step and the step solved again
// whole. The runs must leave islands out (the test is not vacuous), and the guessless ones must
// solve steps again.
#include "world_access.h"
#include "world_helpers.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <functional>
#include <random>
#include <string>
#include <vector>

namespace chain::testing {
namespace {

struct Case {
  std::string name;
  std::function<void(World&)> build;
  int steps;
  // Calls made before step k (from 0), the same in both worlds.
  std::function<void(World&, int)> before_step = [](World&, int) {};
  WorldDef def = WorldDef{};
};

// Columns of boxes falling onto a floor and three thin shelves, where they pile and rest while
// the later columns still fall beside them.
void rain(World& w) {
  add_floor(w, 60.0);
  for (int s = 0; s < 3; ++s)
    w.create_body(static_box(-20.0 + 20.0 * s, 4.0 + 3.0 * s, 4.0, 0.01));
  std::mt19937 next(2024u);
  for (int c = 0; c < 40; ++c) {
    double y = 1.0 + (next() % 100) * 0.15;
    for (int k = 0; k < 5; ++k) {
      const double half = 0.15 + (next() % 100) * 0.004;
      w.create_body(dynamic_box(-28.0 + 1.4 * c, y, half));
      y += 2.0 * half + 0.3 + (next() % 10) * 0.05;
    }
  }
}

// Stacks at rest, struck from the side one after another by boxes thrown at 40 m/s.
void smash(World& w) {
  add_floor(w, 100.0);
  for (int s = 0; s < 6; ++s) {
    for (int k = 0; k < 6; ++k)
      w.create_body(dynamic_box(8.0 * s, 0.5 + k));
  }
  for (int p = 0; p < 3; ++p) {
    BodyDef d = dynamic_box(-20.0 - 25.0 * p, 0.5 + p, 0.4, 3.0);
    d.velocity = {40.0, 0.0};
    w.create_body(d);
  }
}

// A blade pushing a train of crates into crates at rest, 1.2 m apart.
void bulldozer(World& w) {
  add_floor(w, 200.0);
  w.create_body(kinematic_box(-2.0, 1.0, 0.5, 1.0, {3.0, 0.0}));
  for (int k = 0; k < 30; ++k)
    w.create_body(dynamic_box(1.0 + 1.2 * k, 0.5, 0.45));
}

// Rough crates stacked at rest beside a rough row pushed along the same rough floor.
void rough(World& w) {
  BodyDef floor = static_box(0.0, -1.0, 80.0, 1.0);
  floor.friction = 0.6;
  w.create_body(floor);
  for (int c = 0; c < 8; ++c) {
    for (int k = 0; k < 4; ++k) {
      BodyDef d = dynamic_box(20.0 + 1.5 * c, 0.5 + k);
      d.friction = 0.5;
      w.create_body(d);
    }
  }
  BodyDef pusher = dynamic_box(-10.0, 0.5);
  pusher.friction = 0.5;
  w.set_drive(w.create_body(pusher), {2.0, 0.0}, DriveAxes::kX);
  for (int i = 0; i < 6; ++i) {
    BodyDef d = dynamic_box(-8.0 + i, 0.5);
    d.friction = 0.5;
    w.create_body(d);
  }
}

// A row squeezed between two walls (remembered squeezes, crush events every step) beside piles
// at rest, and a lift that rises into a ceiling with a box on it.
void squeeze(World& w) {
  add_floor(w, 60.0);
  w.create_body(static_box(-20.0, 2.0, 0.5, 2.0));
  w.create_body(static_box(-14.05, 2.0, 0.5, 2.0));
  for (int i = 0; i < 5; ++i)
    w.create_body(dynamic_box(-18.5 + 1.1 * i, 0.5));
  for (int c = 0; c < 5; ++c) {
    for (int k = 0; k < 5; ++k)
      w.create_body(dynamic_box(5.0 + 2.0 * c, 0.5 + k));
  }
  w.create_body(static_box(30.0, 6.0, 3.0, 0.5));
  w.create_body(kinematic_box(30.0, 0.5, 2.0, 0.5, {0.0, 1.0}));
  w.create_body(dynamic_box(30.0, 1.5));
}

// A pyramid of 1,830 boxes at rest, and a pusher (body 1) against a row of 1,500 touching boxes.
void pyramid_and_row(World& w) {
  add_floor(w, 2000.0);
  w.create_body(dynamic_box(-1.0, 0.5));
  for (int i = 0; i < 1500; ++i)
    w.create_body(dynamic_box(static_cast<double>(i), 0.5));
  for (int row = 0; row < 60; ++row) {
    for (int k = 0; k < 60 - row; ++k)
      w.create_body(dynamic_box(-200.0 + k + 0.5 * row, 0.5 + row));
  }
}

std::vector<Case> cases() {
  std::vector<Case> list;
  list.push_back({"rain", rain, 300});
  list.push_back({"smash", smash, 240});
  list.push_back({"bulldozer", bulldozer, 240});
  list.push_back({"rough", rough, 240});
  list.push_back({"squeeze", squeeze, 200});
  // The API at work on resting islands: a body's velocity set, a drive set and cleared, bodies
  // destroyed from a pile and created above one, every few steps.
  list.push_back({"api", rain, 300, [](World& w, int k) {
                    const BodyId some{static_cast<std::uint32_t>(4 + (k * 37) % 200)};
                    if (k % 23 == 5 && w.contains(some)) w.set_velocity(some, {0.5, 2.0});
                    if (k % 31 == 7 && w.contains(some)) w.set_drive(some, {0.0, 0.0});
                    if (k % 31 == 17 && w.contains(some)) w.clear_drive(some);
                    if (k % 19 == 11 && w.contains(some)) w.destroy_body(some);
                    if (k % 13 == 3)
                      w.create_body(dynamic_box(-28.0 + 1.4 * ((k * 7) % 40), 9.0, 0.2));
                  }});
  // A budget that a resting pyramid spends most of: once a pusher starts into a long row, every
  // step that solved both would be cut, so a step that leaves the pyramid out must count what it
  // spent and be cut (and solved whole) too.
  Case cut{"budget", pyramid_and_row, 160, [](World& w, int k) {
             if (k == 60) w.set_drive(BodyId{1}, {3.0, 0.0}, DriveAxes::kX);
           }};
  cut.def.budget_per_body = 1;
  list.push_back(cut);
  // Boxes created all at one point beside piles at rest, on a small budget: gatherings that meet
  // the whole new pile are charged to it (StepContext::charge_met), and steps run out of it.
  Case pile{"pile", rain, 260, [](World& w, int k) {
              if (k == 150) {
                for (int i = 0; i < 48; ++i)
                  w.create_body(dynamic_box(25.0, 3.0, 0.3));
              }
            }};
  pile.def.budget_per_body = 2;
  list.push_back(pile);
  // A change of dt: the islands resting at the old one are solved again.
  list.push_back({"dt", rain, 300, [](World&, int) {}});
  return list;
}

// Steps two worlds in lockstep and compares everything a step reports about every body.
struct Tally {
  std::uint64_t resting = 0;  // bodies left out, summed over the steps
  std::uint64_t redone = 0;
  std::vector<std::uint32_t> resting_at;  // bodies left out, step by step
};

Tally lockstep(const Case& c, int threads, bool guess, bool weigh = false) {
  WorldDef left = c.def, whole = c.def;
  left.threads = whole.threads = threads;
  whole.skip_rest = false;
  World a(left), b(whole);
  detail::WorldAccess::impl(a).islands.guess(guess);
  detail::WorldAccess::impl(a).islands.weigh(weigh);
  c.build(a);
  c.build(b);
  Tally run;
  for (int k = 0; k < c.steps; ++k) {
    c.before_step(a, k);
    c.before_step(b, k);
    const double dt = c.name == "dt" && k >= 150 ? 1.0 / 30.0 : 1.0 / 60.0;
    a.step(dt);
    b.step(dt);
    run.resting += a.last_step_stats().resting;
    run.resting_at.push_back(a.last_step_stats().resting);
    run.redone += a.last_step_stats().redone;
    const auto ids = static_cast<std::uint32_t>(detail::WorldAccess::impl(a).slot_of_id.size());
    std::size_t apart = 0;
    for (std::uint32_t i = 0; i < ids; ++i) {
      const BodyId id{i};
      if (!a.contains(id)) continue;
      const Vec2 p = a.position(id), q = b.position(id), u = a.velocity(id), v = b.velocity(id);
      if (bits(p.x) != bits(q.x) || bits(p.y) != bits(q.y) || bits(u.x) != bits(v.x) ||
          bits(u.y) != bits(v.y) || a.touching_flags(id) != b.touching_flags(id))
        ++apart;
    }
    EXPECT_EQ(apart, 0u) << "after step " << k;
    const auto ca = a.crush_events(), cb = b.crush_events();
    EXPECT_EQ(ca.size(), cb.size()) << "after step " << k;
    for (std::size_t e = 0; e < std::min(ca.size(), cb.size()); ++e) {
      EXPECT_EQ(ca[e].body.value, cb[e].body.value);
      EXPECT_EQ(ca[e].anchor.value, cb[e].anchor.value);
      EXPECT_EQ(ca[e].blocker.value, cb[e].blocker.value);
    }
    if (apart > 0) break;
  }
  return run;
}

TEST(Islands, LeavingRestingIslandsOutChangesNoBitOnAnyThreadCount) {
  for (const Case& c : cases()) {
    for (const int threads : {1, 2, 3, 8}) {
      SCOPED_TRACE(c.name + ", threads " + std::to_string(threads));
      const Tally run = lockstep(c, threads, true);
      // (The budget's steps leaving islands out are all cut, and solved again.)
      EXPECT_GT(run.resting + run.redone, 0u) << "no island was left out";
    }
  }
}

TEST(Islands, AStepThatMeetsAnIslandLeftOutIsSolvedAgainToTheSameBits) {
  std::uint64_t redone = 0;
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.name);
    const Tally run = lockstep(c, 1, false);
    EXPECT_GT(run.resting + run.redone, 0u) << "no island was left out";
    redone += run.redone;
  }
  EXPECT_GT(redone, 10u) << "steps solved again";
}

// Leaving islands out costs checks of every solved body (islands.h); an island that touches
// nothing would save only its integration. Boxes floating at rest without gravity are left out
// only when asked to be whatever it pays; boxes resting on shelves are left out either way, and
// the bits are those of solving every body in all of these.
TEST(Islands, IslandsThatWouldResolveNothingAreLeftOutOnlyWhereThatPays) {
  Case floating{"floating",
                [](World& w) {
                  for (int r = 0; r < 10; ++r) {
                    for (int c = 0; c < 20; ++c)
                      w.create_body(dynamic_box(2.0 * c, 2.0 * r, 0.5));
                  }
                  BodyDef d = dynamic_box(-10.0, 0.0, 0.5);
                  d.velocity = {-1.0, 0.0};
                  w.create_body(d);
                },
                300};
  floating.def.gravity = {0.0, 0.0};
  EXPECT_GT(lockstep(floating, 1, true, false).resting, 0u) << "left out when asked to be";
  EXPECT_EQ(lockstep(floating, 1, true, true).resting, 0u) << "left out where it does not pay";
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.name);
    const Tally run = lockstep(c, 1, true, true);
    if (c.name == "rain") {
      EXPECT_GT(run.resting, 0u) << "piles at rest resolve their supports";
    }
  }
}

// A search that does not pay is made again later: 100 boxes rest on the floor (one pair each)
// while 280 fall from 40 m, which takes them about 170 steps; once they have landed in columns
// and rest, what is left out pays, and is left out (a platform moving far away keeps the world
// from being at rest as a whole, which rest.h would skip whole).
TEST(Islands, LeavingIslandsOutResumesOnceItPays) {
  Case landing{"landing",
               [](World& w) {
                 add_floor(w, 200.0);
                 w.create_body(kinematic_box(150.0, 20.0, 1.0, 0.25, {1.0, 0.0}));
                 for (int k = 0; k < 100; ++k)
                   w.create_body(dynamic_box(2.0 * k, 0.5));
                 for (int c = 0; c < 14; ++c) {
                   for (int k = 0; k < 20; ++k)
                     w.create_body(dynamic_box(-100.0 + 2.0 * c, 40.0 + 1.5 * k));
                 }
               },
               420};
  for (const int threads : {1, 2}) {
    SCOPED_TRACE("threads " + std::to_string(threads));
    const Tally asked = lockstep(landing, threads, true, false);
    const Tally weighed = lockstep(landing, threads, true, true);
    auto left_out = [](const Tally& t, int from, int to) {
      std::uint64_t sum = 0;
      for (int k = from; k < to && k < static_cast<int>(t.resting_at.size()); ++k)
        sum += t.resting_at[k];
      return sum;
    };
    EXPECT_GT(left_out(asked, 10, 150), 0u) << "the boxes on the floor, left out when asked";
    EXPECT_EQ(left_out(weighed, 10, 150), 0u) << "solved while 400 boxes fall";
    EXPECT_GT(left_out(weighed, 360, 420), 0u) << "left out once everything rests";
  }
}

}  // namespace
}  // namespace chain::testing
