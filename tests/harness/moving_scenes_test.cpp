// SPDX-License-Identifier: MIT
// The moving scenes (bench/scenes/moving.cpp) and the stack wall: each builds a valid scene that
// states where every dynamic body ends, scales with its size parameter, states the answers its
// recipe derives, and the modern solver meets them, as Box2D does at these sizes.
#include "campaign/stress.h"
#include "scenes/scene_library.h"

#include <gtest/gtest.h>

#include <set>
#include <string>
#include <vector>

namespace chainbench {
namespace {

const std::vector<std::string> kMoving = {"rain", "smash", "bulldozer"};

// The expectation entries that state where `body` ends (unwindowed center or bounds).
std::vector<const Expectation*> final_entries(const Scene& s, std::size_t body) {
  std::vector<const Expectation*> out;
  for (const Expectation& e : s.expect) {
    if (e.body == body && !e.windowed()) out.push_back(&e);
  }
  return out;
}

TEST(MovingScenes, EachStatesWhereEveryDynamicBodyEnds) {
  for (const std::string& name : kMoving) {
    SCOPED_TRACE(name);
    const SceneRecipe* recipe = find_recipe(name);
    ASSERT_NE(recipe, nullptr);
    EXPECT_EQ(recipe->family, "moving");
    for (const int steps : {1, 60, 120, 400}) {
      const Scene s = make_scene(name, {"steps=" + std::to_string(steps)});
      const auto issues = validate(s);
      ASSERT_TRUE(issues.empty()) << issues[0].path << ": " << issues[0].reason;
      std::set<std::size_t> windowed;  // bodies with a fact for every state
      for (const Expectation& e : s.expect) {
        if (e.windowed()) windowed.insert(e.body);
      }
      for (std::size_t b = 0; b < s.bodies.size(); ++b) {
        if (s.bodies[b].kind != BodyKind::kDynamic) continue;
        // Rain's piles are stated still at every state; every other body has its end stated.
        const bool stated = !final_entries(s, b).empty() || windowed.count(b) > 0;
        EXPECT_TRUE(stated) << s.bodies[b].name << " at " << steps << " steps";
      }
    }
  }
}

TEST(MovingScenes, ScaleWithTheirSizeParameter) {
  for (const auto& [name, key] :
       {std::pair{"rain", "cols"}, std::pair{"smash", "lanes"}, std::pair{"bulldozer", "lanes"}}) {
    SCOPED_TRACE(name);
    const SceneRecipe& recipe = *find_recipe(name);
    SceneParams params;
    for (const SceneParam& p : all_params(recipe))
      params.set(p.key, p.value);
    const std::size_t small = recipe.body_count(params);
    const int larger = 10 * static_cast<int>(params.get(key));
    params.set(key, larger);
    const std::size_t large = recipe.body_count(params);
    // Ten times the size is ten times the bodies, give or take what a scene has once (walls, the
    // bulldozer's outermost row: 10 of 230 bodies) and the rain's random column heights.
    const double ratio = static_cast<double>(large) / static_cast<double>(small);
    EXPECT_GT(ratio, 9.0);
    EXPECT_LT(ratio, 11.0);
    EXPECT_EQ(make_scene(name, {std::string(key) + "=" + std::to_string(larger)}).bodies.size(),
              large);
  }
  // The benchmark's large sizes are about 100,000 bodies.
  EXPECT_GT(make_scene("smash", {"lanes=2500"}).bodies.size(), 100'000u);
}

// One column of 6 boxes 1 m from the block, the block as heavy as it: the block strikes it after
// 1 m at 4 m/s (0.25 s), and the two move off at v / 2, so at 1.5 s the block's face is
// 2.5 + 1 + 2 (1.25) = 6 m along and its centre 1 m behind that.
TEST(MovingScenes, SmashSharesTheBlocksMomentumWithEachColumn) {
  const Scene s = make_scene("smash", {"lanes=1", "cols=1", "steps=90"});
  ASSERT_EQ(s.bodies[4].name, "lane0_block");  // after the lane's four walls
  const Expectation& block = *final_entries(s, 4)[0];
  EXPECT_NEAR(block.center.x, 5.0, 1e-12);
  // Gathered at the block's face: the column's boxes end half a box ahead of it.
  const Expectation& box = *final_entries(s, 5)[0];
  EXPECT_NEAR(box.center.x, 6.5, 1e-12);
  // Up to a step late at the strike, at most (v - v / 2) dt ahead: 3.3 cm beside kVisible.
  EXPECT_NEAR(block.tolerance, build::kVisible + 2.0 / 60.0, 1e-12);
}

// A blade at 2 m/s for 2 s meets the crates whose back faces are within 4 m, plus 1 m for each
// crate already packed in front of it; those end packed in order against it, the rest unmoved.
TEST(MovingScenes, BulldozerPacksTheCratesItMeetsAheadOfTheBlade) {
  const Scene s = make_scene("bulldozer", {"lanes=1", "rows=1", "spacing=1"});
  std::vector<double> packed, untouched;
  for (std::size_t b = 0; b < s.bodies.size(); ++b) {
    if (s.bodies[b].kind != BodyKind::kDynamic || s.bodies[b].center.y != 1.25) continue;
    const Expectation& end = *final_entries(s, b)[0];
    ASSERT_EQ(end.kind, Expectation::Kind::kCenter);
    (end.center.x == s.bodies[b].center.x ? untouched : packed).push_back(end.center.x);
  }
  ASSERT_FALSE(packed.empty());
  for (std::size_t k = 0; k < packed.size(); ++k)
    EXPECT_NEAR(packed[k], 4.0 + 0.5 + static_cast<double>(k), 1e-12);
  for (const double x : untouched)
    EXPECT_GT(x - 0.5, 4.0 + static_cast<double>(packed.size()));
}

// The rain's drops slide off their shelves and land on their columns: a run long enough for every
// drop to land states each on the column's top, one box above the last.
TEST(MovingScenes, RainLandsEachDropOnItsColumn) {
  const Scene s = make_scene("rain", {"cols=1", "depth=1", "steps=200"});
  std::vector<double> landed;
  for (std::size_t b = 0; b < s.bodies.size(); ++b) {
    if (s.bodies[b].name.rfind("drop", 0) != 0) continue;
    const Expectation& end = *final_entries(s, b)[0];
    if (end.kind == Expectation::Kind::kCenter && end.center.x != s.bodies[b].center.x)
      landed.push_back(end.center.y);
  }
  ASSERT_GE(landed.size(), 4u);
  for (std::size_t k = 0; k < landed.size(); ++k)
    EXPECT_EQ(landed[k], 1.5 + static_cast<double>(k));  // on a one-box pile
}

TEST(MovingScenes, ModernSolverAndBox2dMeetEveryAnswer) {
  for (const std::string& name : kMoving) {
    for (const std::vector<std::string>& sets :
         {std::vector<std::string>{}, std::vector<std::string>{"steps=60"}}) {
      const StressCase c{"moving", name, sets, false};
      SCOPED_TRACE(c.label());
      const StressVerdict chain = run_stress_case(c, parse_engine_spec("chain"), 120.0);
      EXPECT_EQ(chain.verdict(), VerdictClass::kOk) << chain.verdict_detail();
      // An independent engine meets the same answers: they are not the chain solver's own.
      const StressVerdict box2d = run_stress_case(c, parse_engine_spec("box2d"), 120.0);
      EXPECT_TRUE(box2d.expect_pass) << box2d.verdict_detail();
    }
  }
}

// A smash wide enough that bodies are renumbered and, later, thrown far enough to be filed again
// in the broadphase: the refiling once wrote through a slot number from before the renumbering
// and corrupted the heap (a crash, or under ASan a report). Every answer is met.
TEST(MovingScenes, WideSmashRenumbersAndRefilesSafely) {
  const StressCase c{"moving", "smash", {"lanes=250"}, false};
  const StressVerdict chain = run_stress_case(c, parse_engine_spec("chain"), 300.0);
  EXPECT_EQ(chain.verdict(), VerdictClass::kOk) << chain.verdict_detail();
}

TEST(StackWall, IsColumnsOfBoxesAtRest) {
  const Scene s = make_scene("stack_wall", {"cols=500", "height=10"});
  EXPECT_EQ(s.bodies.size(), 5001u);
  ASSERT_EQ(s.expect.size(), 1u);
  EXPECT_EQ(s.expect[0].kind, Expectation::Kind::kMoved);
  const StressVerdict v = run_stress_case({"stacking", "stack_wall", {"cols=50"}, false},
                                          parse_engine_spec("chain"), 60.0);
  EXPECT_EQ(v.verdict(), VerdictClass::kOk) << v.verdict_detail();
}

}  // namespace
}  // namespace chainbench
