// SPDX-License-Identifier: MIT
// The chain engine's skip_rest key: on every built-in scene, skipping the steps a world at rest
// would rebuild gives the same bits as solving every step, on one thread and on two, and the
// scenes that come to rest do skip.
#include "engines/registry.h"
#include "run/runner.h"
#include "scenes/scene_library.h"

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <optional>
#include <set>
#include <string>

namespace chainbench {
namespace {

double counter(const EngineRun& run, const std::string& name) {
  const std::optional<double> value = run.counter(name);
  if (!value) ADD_FAILURE() << "no counter " << name;
  return value.value_or(-1.0);
}

bool same_bits(const std::vector<Vec2d>& a, const std::vector<Vec2d>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (std::bit_cast<std::uint64_t>(a[i].x) != std::bit_cast<std::uint64_t>(b[i].x) ||
        std::bit_cast<std::uint64_t>(a[i].y) != std::bit_cast<std::uint64_t>(b[i].y))
      return false;
  }
  return true;
}

TEST(SkipRest, EveryBuiltInSceneGivesTheBitsOfSolvingEveryStep) {
  // Scenes built at rest, which must skip most of their steps (the others move to the end, or
  // come to rest later than 150 steps, or their bodies keep a velocity).
  const std::set<std::string> resting = {"stack",      "pyramid",          "many_pyramids",
                                         "stack_wall", "mass_ratio_stack", "static_squeeze"};
  std::size_t skipping = 0;
  for (const SceneRecipe& r : scene_library()) {
    SCOPED_TRACE(r.name);
    // many_pyramids is 22,000 boxes by default: a few pyramids show the same.
    const Scene scene =
        make_scene(r.name, r.name == "many_pyramids"
                               ? std::vector<std::string>{"rows=2", "cols=3", "steps=150"}
                               : std::vector<std::string>{"steps=150"});
    const EngineRun solved =
        run_engine(scene, parse_engine_spec("chain:skip_rest=0"), RunOptions{});
    EXPECT_EQ(counter(solved, "skipped_steps"), 0.0);
    for (const char* spec : {"chain", "chain:threads=2"}) {
      SCOPED_TRACE(spec);
      const EngineRun run = run_engine(scene, parse_engine_spec(spec), RunOptions{});
      EXPECT_EQ(run.final_state, solved.final_state);
      EXPECT_TRUE(same_bits(run.final_positions, solved.final_positions));
      const double skipped = counter(run, "skipped_steps");
      if (resting.count(r.name)) {
        EXPECT_GE(skipped, 100.0) << "of 150 steps";
      }
      if (skipped > 0.0) ++skipping;
    }
  }
  EXPECT_GE(skipping, 2 * resting.size());
}

}  // namespace
}  // namespace chainbench
