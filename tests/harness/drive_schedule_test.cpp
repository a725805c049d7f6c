// SPDX-License-Identifier: MIT
// The drive schedule follows events, not every driver each step: whatever the drivers (several
// per body, overlapping, empty, never ending), the drives it holds, the drives it reports begun
// or changed and the bodies it reports released are at every step those a scan of every driver
// finds, in the order the bodies were first driven; also across jumps and steps back.
#include "model/drive_schedule.h"

#include <gtest/gtest.h>

#include <limits>
#include <optional>
#include <random>
#include <vector>

namespace chainbench {
namespace {

// Per driven body (first driven first): its drive at step n, by scanning every driver.
std::vector<std::optional<Drive>> scan(const Scene& s, const std::vector<std::size_t>& bodies,
                                       int n) {
  std::vector<std::optional<Drive>> out(bodies.size());
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    for (const Driver& d : s.drivers) {
      if (d.body == bodies[b] && d.from_step <= n && n < d.to_step)
        out[b] = Drive{d.body, d.velocity, d.hold_x, d.hold_y};
    }
  }
  return out;
}

Scene random_drivers(std::mt19937& rng) {
  Scene s;
  s.bodies.resize(12);
  std::uniform_int_distribution<int> body(0, 11), step(0, 40), len(-3, 25), axes(0, 2), v(-3, 3);
  const int count = std::uniform_int_distribution<int>(0, 30)(rng);
  for (int k = 0; k < count; ++k) {
    Driver d;
    d.body = static_cast<std::size_t>(body(rng));
    d.from_step = step(rng);
    const int l = len(rng);
    d.to_step = l > 22 ? std::numeric_limits<int>::max() : d.from_step + std::max(0, l);
    d.velocity = {static_cast<double>(v(rng)), static_cast<double>(v(rng))};
    const int a = axes(rng);
    d.hold_x = a != 1;
    d.hold_y = a != 0;
    s.drivers.push_back(d);
  }
  return s;
}

void expect_matches(const Scene& s, DriveSchedule& schedule, int n,
                    const std::vector<std::optional<Drive>>& before) {
  std::vector<std::size_t> bodies;
  for (const Driver& d : s.drivers) {
    if (std::find(bodies.begin(), bodies.end(), d.body) == bodies.end()) bodies.push_back(d.body);
  }
  schedule.advance(n);
  const std::vector<std::optional<Drive>> now = scan(s, bodies, n);
  std::vector<Drive> active, changed;
  std::vector<std::size_t> released;
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    if (now[b]) active.push_back(*now[b]);
    if (now[b] && (!before[b] || !(*before[b] == *now[b]))) changed.push_back(*now[b]);
    if (!now[b] && before[b]) released.push_back(bodies[b]);
  }
  EXPECT_EQ(std::vector<Drive>(schedule.active().begin(), schedule.active().end()), active);
  EXPECT_EQ(std::vector<Drive>(schedule.changed().begin(), schedule.changed().end()), changed);
  EXPECT_EQ(std::vector<std::size_t>(schedule.released().begin(), schedule.released().end()),
            released);
}

std::vector<std::optional<Drive>> held_at(const Scene& s, int n) {
  std::vector<std::size_t> bodies;
  for (const Driver& d : s.drivers) {
    if (std::find(bodies.begin(), bodies.end(), d.body) == bodies.end()) bodies.push_back(d.body);
  }
  return n < 0 ? std::vector<std::optional<Drive>>(bodies.size()) : scan(s, bodies, n);
}

TEST(DriveSchedule, StepByStepItHoldsWhatAScanOfEveryDriverFinds) {
  std::mt19937 rng(20);
  for (int trial = 0; trial < 300; ++trial) {
    SCOPED_TRACE(trial);
    const Scene s = random_drivers(rng);
    DriveSchedule schedule(s);
    for (int n = 0; n < 70; ++n) {
      SCOPED_TRACE(n);
      expect_matches(s, schedule, n, held_at(s, n - 1));
      if (::testing::Test::HasFailure()) return;
    }
  }
}

TEST(DriveSchedule, JumpsAndStepsBackCompareWithTheStepLastAdvancedTo) {
  std::mt19937 rng(21);
  std::uniform_int_distribution<int> next(0, 60);
  for (int trial = 0; trial < 200; ++trial) {
    SCOPED_TRACE(trial);
    const Scene s = random_drivers(rng);
    DriveSchedule schedule(s);
    int last = -1;
    for (int k = 0; k < 12; ++k) {
      const int n = next(rng);
      SCOPED_TRACE(n);
      expect_matches(s, schedule, n, held_at(s, last));
      if (::testing::Test::HasFailure()) return;
      last = n;
    }
  }
}

// The example kept with its answer: a body slid for steps 2..4 and then held still from 5 on,
// and a second body driven from 3 to 6 by one driver and from 4 to 5 by a later one that wins.
TEST(DriveSchedule, ASlideThenAHoldAndALaterDriverThatWins) {
  Scene s;
  s.bodies.resize(2);
  s.drivers = {{0, {2, 0}, 2, 5, true, false},
               {0, {0, 0}, 5, std::numeric_limits<int>::max(), true, false},
               {1, {1, 1}, 3, 6},
               {1, {-1, 0}, 4, 5}};
  DriveSchedule schedule(s);
  std::vector<std::size_t> active_count;
  for (int n = 0; n < 8; ++n) {
    schedule.advance(n);
    active_count.push_back(schedule.active().size());
    if (n == 4) {
      ASSERT_EQ(schedule.active().size(), 2u);
      EXPECT_EQ(schedule.active()[1].velocity.x, -1.0);  // the later driver of body 1
      ASSERT_EQ(schedule.changed().size(), 1u);
      EXPECT_EQ(schedule.changed()[0].body, 1u);
    }
    if (n == 5) {
      ASSERT_EQ(schedule.changed().size(), 2u);  // body 0 now held still, body 1 back to (1, 1)
      EXPECT_EQ(schedule.changed()[0].velocity.x, 0.0);
      EXPECT_EQ(schedule.changed()[1].velocity.x, 1.0);
    }
    if (n == 6) {
      ASSERT_EQ(schedule.released().size(), 1u);
      EXPECT_EQ(schedule.released()[0], 1u);
      EXPECT_TRUE(schedule.changed().empty());
    }
  }
  EXPECT_EQ(active_count, (std::vector<std::size_t>{0, 0, 1, 2, 2, 2, 1, 1}));
}

}  // namespace
}  // namespace chainbench
