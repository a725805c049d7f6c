// SPDX-License-Identifier: MIT
// Built-in scenes: every one builds a valid scene with its defaults; --set is checked before
// anything is built.
#include "scenes/scene_library.h"
#include "support/input_error.h"

#include <gtest/gtest.h>

namespace chainbench {
namespace {

std::string error_of(const std::string& name, const std::vector<std::string>& sets) {
  try {
    make_scene(name, sets);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(SceneLibrary, EveryRecipeBuildsAValidSceneWithItsDefaults) {
  ASSERT_GE(scene_library().size(), 14u);
  for (const SceneRecipe& r : scene_library()) {
    SCOPED_TRACE(r.name);
    const Scene s = make_scene(r.name, {});
    EXPECT_TRUE(validate(s).empty()) << validate(s)[0].path << ": " << validate(s)[0].reason;
    EXPECT_EQ(s.steps, r.steps);
    SceneParams defaults;
    for (const SceneParam& p : all_params(r))
      defaults.set(p.key, p.value);
    EXPECT_EQ(s.bodies.size(), r.body_count(defaults));
    EXPECT_FALSE(r.description.empty());
  }
}

TEST(SceneLibrary, SizesTheIssueNames) {
  EXPECT_EQ(make_scene("stack", {}).bodies.size(), 16u);                   // 15 boxes + ground
  EXPECT_EQ(make_scene("pyramid", {"base=100"}).bodies.size(), 5051u);     // large_pyramid
  EXPECT_EQ(make_scene("many_pyramids", {}).bodies.size(), 22000u + 20u);  // + 20 shelves
  EXPECT_EQ(make_scene("overlap_recovery", {}).bodies.size(), 11u);        // base-4 pyramid
}

TEST(SceneLibrary, SceneDeclaresOnlyWhatItNeeds) {
  EXPECT_FALSE(make_scene("push_row", {}).has_gravity());  // top-down
  EXPECT_TRUE(make_scene("push_stack", {}).has_gravity());
  for (const SceneRecipe& r : scene_library()) {
    const Scene s = make_scene(r.name, {});
    EXPECT_EQ(s.friction, 0.0) << r.name;
    EXPECT_FALSE(s.rotation) << r.name;
  }
}

TEST(SceneLibrary, SetChangesParametersAndCommonKeys) {
  const Scene s = make_scene("push_row", {"n=3", "speed=5", "steps=7", "dt=0.01", "friction=0.5"});
  EXPECT_EQ(s.bodies.size(), 4u);
  EXPECT_EQ(s.drivers[0].velocity.x, 5.0);
  EXPECT_EQ(s.steps, 7);
  EXPECT_EQ(s.dt, 0.01);
  EXPECT_EQ(s.friction, 0.5);
}

TEST(SceneLibrary, BadSetsAreRefusedWithTheReason) {
  EXPECT_NE(error_of("nope", {}).find("unknown scene \"nope\""), std::string::npos);
  EXPECT_NE(error_of("stack", {"height=3"}).find("has no parameter \"height\""), std::string::npos);
  EXPECT_NE(error_of("stack", {"n=abc"}).find("not a number"), std::string::npos);
  EXPECT_NE(error_of("stack", {"n=nan"}).find("not a finite number"), std::string::npos);
  EXPECT_NE(error_of("stack", {"n=1e400"}).find("not a finite number"), std::string::npos);
  EXPECT_NE(error_of("stack", {"n=2.5"}).find("whole number"), std::string::npos);
  EXPECT_NE(error_of("stack", {"n=0"}).find("out of range"), std::string::npos);
  EXPECT_NE(error_of("stack", {"n"}).find("KEY=VALUE"), std::string::npos);
  EXPECT_NE(error_of("push_row", {"n=1e12"}).find("out of range"), std::string::npos);
  EXPECT_NE(error_of("stack", {"dt=0"}).find("out of range"), std::string::npos);
}

TEST(SceneLibrary, ParameterProductsBeyondTheBodyLimitAreRefusedBeforeBuilding) {
  // Each value is in range; together they would be 202 million boxes.
  const std::string msg = error_of("many_pyramids", {"rows=200", "cols=200", "base=100"});
  EXPECT_NE(msg.find("more than the limit"), std::string::npos) << msg;
}

}  // namespace
}  // namespace chainbench

namespace chainbench {
namespace {

// The default suite names each scene once, every one a recipe the library builds.
TEST(SceneLibrary, TheDefaultSuiteNamesRecipesOnce) {
  const std::vector<std::string>& suite = default_suite();
  ASSERT_FALSE(suite.empty());
  for (std::size_t i = 0; i < suite.size(); ++i) {
    EXPECT_NE(find_recipe(suite[i]), nullptr) << suite[i];
    for (std::size_t j = 0; j < i; ++j) {
      EXPECT_NE(suite[i], suite[j]) << "named twice";
    }
  }
}

}  // namespace
}  // namespace chainbench
