// SPDX-License-Identifier: MIT
// A StateFeed holds exactly what reading the whole state every step gives, before and after each
// step, and where the engine lists its changes (the chain engine), the list is exactly the bodies
// whose bits changed; the metrics computed from those lists are those of a full scan.
#include "run/state_feed.h"

#include "engines/engine_spec.h"
#include "engines/registry.h"
#include "judge/metrics.h"
#include "scenes/scene_library.h"

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <string>
#include <vector>

namespace chainbench {
namespace {

bool same_bits(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

// Bodies whose position, velocity or angle differ in bits between a and b, or are NaN.
std::vector<std::uint32_t> differing(const BodyState& a, const BodyState& b) {
  std::vector<std::uint32_t> out;
  for (std::size_t i = 0; i < a.position.size(); ++i) {
    const bool same = same_bits(a.position[i].x, b.position[i].x) &&
                      same_bits(a.position[i].y, b.position[i].y) &&
                      same_bits(a.velocity[i].x, b.velocity[i].x) &&
                      same_bits(a.velocity[i].y, b.velocity[i].y) &&
                      same_bits(a.angle[i], b.angle[i]) && b.position[i].x == b.position[i].x &&
                      b.position[i].y == b.position[i].y;
    if (!same) out.push_back(static_cast<std::uint32_t>(i));
  }
  return out;
}

void expect_same_state(const BodyState& got, const BodyState& want, int step) {
  EXPECT_TRUE(differing(got, want).empty()) << "step " << step;
}

// Steps two copies of one engine: one read through a feed, the other read whole every step.
void feed_matches_full_reads(const std::string& engine, const std::string& scene_name,
                             const std::vector<std::string>& sets, bool lists) {
  SCOPED_TRACE(engine + " " + scene_name);
  const Scene scene = make_scene(scene_name, sets);
  const auto fed = make_engine(parse_engine_spec(engine), scene);
  const auto whole = make_engine(parse_engine_spec(engine), scene);
  StateFeed feed(*fed, scene.bodies.size());
  BodyState previous(scene.bodies.size()), now(scene.bodies.size());
  feed.read();
  whole->read_state(previous);
  expect_same_state(feed.after(), previous, 0);
  MetricsRecorder listed(scene, MetricSelection{}), full(scene, MetricSelection{});
  full.scan_every_body();
  std::size_t changes = 0;
  for (int step = 0; step < scene.steps; ++step) {
    fed->step(step);
    whole->step(step);
    feed.read();
    whole->read_state(now);
    expect_same_state(feed.before(), previous, step);
    expect_same_state(feed.after(), now, step + 1);
    ASSERT_EQ(feed.changed() != nullptr, lists);
    if (lists) {
      EXPECT_EQ(*feed.changed(), differing(previous, now)) << "step " << step + 1;
      changes += feed.changed()->size();
    }
    listed.observe(feed.before(), feed.after(), step + 1, false, false, feed.changed());
    full.observe(previous, now, step + 1, false);
    std::swap(previous, now);
  }
  if (lists) {
    EXPECT_GT(changes, 0u);
  }
  const Metrics a = listed.result(previous), b = full.result(previous);
  EXPECT_EQ(*a.efd_total, *b.efd_total);
  EXPECT_EQ(*a.max_penetration, *b.max_penetration);
  EXPECT_EQ(*a.peak_speed, *b.peak_speed);
  EXPECT_EQ(a.peak_speed_body, b.peak_speed_body);
  EXPECT_EQ(*a.blow_up, *b.blow_up);
  EXPECT_EQ(a.escaped, b.escaped);
  EXPECT_EQ(a.tunnel_count, b.tunnel_count);
}

TEST(StateFeed, ChainEngineListsExactlyTheBodiesThatChanged) {
  feed_matches_full_reads("chain", "bulldozer", {"lanes=3", "steps=150"}, true);
  feed_matches_full_reads("chain", "smash", {"lanes=8", "steps=90"}, true);
  feed_matches_full_reads("chain", "rain", {"cols=30", "steps=90"}, true);
  feed_matches_full_reads("chain", "push_row", {"n=40", "steps=60"}, true);
  feed_matches_full_reads("chain", "random_pile", {"n=300", "steps=60"}, true);
}

TEST(StateFeed, AnEngineThatDoesNotListIsReadWhole) {
  feed_matches_full_reads("box2d", "smash", {"lanes=4", "steps=40"}, false);
}

}  // namespace
}  // namespace chainbench
