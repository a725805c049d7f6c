// SPDX-License-Identifier: MIT
// sweep --vary: one built-in scene built once per value of a parameter.
#include "scenes/scene_vary.h"
#include "scenes/scene_library.h"
#include "support/input_error.h"

#include <gtest/gtest.h>

namespace chainbench {
namespace {

TEST(SceneVary, ParsesNumbersAndFractionsAsWritten) {
  const SceneVary v = parse_vary("dt=1/30,1/60,0.004");
  EXPECT_EQ(v.key, "dt");
  EXPECT_EQ(v.texts, (std::vector<std::string>{"1/30", "1/60", "0.004"}));
  ASSERT_EQ(v.values.size(), 3u);
  EXPECT_EQ(v.values[0], 1.0 / 30.0);  // the division a/b itself, bit for bit
  EXPECT_EQ(v.values[1], 1.0 / 60.0);
  EXPECT_EQ(v.values[2], 0.004);
}

TEST(SceneVary, RefusesMalformedListsByName) {
  for (const char* bad :
       {"dt", "=1", "dt=", "dt=1/30,", "dt=1/0", "dt=x", "dt=1/60,1/60", "dt=2/120,1/60"}) {
    SCOPED_TRACE(bad);
    try {
      parse_vary(bad);
      ADD_FAILURE() << "accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()).rfind("--vary", 0), 0u) << e.what();
    }
  }
}

TEST(SceneVary, VaryingTheTimeStepKeepsTheSimulatedTime) {
  const SceneRecipe* recipe = find_recipe("stack");
  ASSERT_NE(recipe, nullptr);
  const SceneVary v = parse_vary("dt=1/30,1/60,1/240");
  for (std::size_t k = 0; k < v.values.size(); ++k) {
    const Scene s = make_varied_scene("stack", {}, v, k);
    EXPECT_EQ(s.dt, v.values[k]);
    EXPECT_NEAR(s.steps * s.dt, recipe->steps / 60.0, 1e-12) << v.texts[k];
  }
  // A given run length is kept as it is.
  EXPECT_EQ(make_varied_scene("stack", {"steps=10"}, v, 0).steps, 10);
}

TEST(SceneVary, OtherParametersTakeTheValueAsIs) {
  const SceneVary v = parse_vary("friction=0,0.5");
  const Scene s = make_varied_scene("stack", {}, v, 1);
  EXPECT_EQ(s.friction, 0.5);
  EXPECT_EQ(s.steps, find_recipe("stack")->steps);
}

TEST(SceneVary, RefusesAKeyTheSceneLacksAValueOutOfRangeOrAKeySetTwice) {
  const auto message = [](const std::vector<std::string>& sets, const char* vary) {
    try {
      make_varied_scene("stack", sets, parse_vary(vary), 0);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(message({}, "bogus=1").find("has no parameter \"bogus\""), std::string::npos);
  EXPECT_NE(message({}, "dt=2").find("--vary dt=2: scene stack takes values in [1e-06, 1]"),
            std::string::npos);
  EXPECT_NE(message({"dt=0.01"}, "dt=1/30").find("--set dt gives it a single value too"),
            std::string::npos);
}

}  // namespace
}  // namespace chainbench
