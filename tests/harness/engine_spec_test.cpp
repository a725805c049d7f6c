// SPDX-License-Identifier: MIT
// Engine specs parse to canonical strings, fill defaults, and refuse what they do not know.
#include "engines/engine_spec.h"
#include "support/input_error.h"

#include <gtest/gtest.h>

namespace chainbench {
namespace {

TEST(EngineSpec, DefaultsAreFilledInCanonicalOrder) {
  EXPECT_EQ(parse_engine_spec("chain").str(),
            "chain:variant=modern,velocity=inelastic,passes=4,budget=64,depth=2048,threads=1,"
            "skip_rest=1");
  EXPECT_EQ(parse_engine_spec("box2d").str(),
            "box2d:vel_iters=8,pos_iters=3,substeps=1,skin=compensate,warm=1,ccd=1,sleep=0");
  // Given out of order, printed in canonical order.
  EXPECT_EQ(parse_engine_spec("box2d:substeps=2,vel_iters=4").str(),
            "box2d:vel_iters=4,pos_iters=3,substeps=2,skin=compensate,warm=1,ccd=1,sleep=0");
}

TEST(EngineSpec, VelocityRuleDefaultsToEachVariantsOwn) {
  EXPECT_EQ(parse_engine_spec("chain:variant=seed2014").get("velocity"), "zero");
  EXPECT_EQ(parse_engine_spec("chain:variant=modern").get("velocity"), "inelastic");
  EXPECT_EQ(parse_engine_spec("chain:variant=seed2014,velocity=inelastic").get("velocity"),
            "inelastic");
}

// Tables and plots label points by the short form; it must name the very setting that ran.
TEST(EngineSpec, ShortFormParsesBackToTheSameSpec) {
  for (const char* text :
       {"chain", "chain:velocity=zero", "chain:variant=seed2014",
        "chain:variant=seed2014,velocity=inelastic", "chain:variant=seed2014,velocity=zero",
        "chain:passes=1,budget=4", "box2d", "box2d:substeps=8,skin=raw"}) {
    const EngineSpec spec = parse_engine_spec(text);
    EXPECT_EQ(parse_engine_spec(spec.label()).str(), spec.str()) << text;
  }
  EXPECT_EQ(parse_engine_spec("chain:variant=seed2014,velocity=zero").label(),
            "chain:variant=seed2014");
  EXPECT_EQ(parse_engine_spec("chain:variant=seed2014,velocity=inelastic").label(),
            "chain:variant=seed2014,velocity=inelastic");
  EXPECT_EQ(parse_engine_spec("chain:variant=modern,velocity=inelastic").label(), "chain");
}

TEST(EngineSpec, RefusesUnknownEnginesKeysAndValues) {
  for (const char* bad :
       {"bullet", "chain:speed=3", "chain:variant=fast", "box2d:vel_iters=0", "box2d:vel_iters=2.5",
        "box2d:vel_iters=abc", "box2d:pos_iters=-1", "chain:passes=1e9", "chain:variant",
        "chain:=3", "box2d:skin=raw,skin=raw", "chain:budget=nan"}) {
    EXPECT_THROW(parse_engine_spec(bad), InputError) << bad;
  }
  try {
    parse_engine_spec("chain:speed=3");
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("unknown key \"speed\""), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("variant"), std::string::npos) << "should list the keys";
  }
}

TEST(EngineSpec, ListsSplitOnCommasThatStartANewEngine) {
  const auto specs =
      parse_engine_list("chain,chain:variant=seed2014,velocity=zero,box2d:vel_iters=4,pos_iters=1");
  ASSERT_EQ(specs.size(), 3u);
  EXPECT_EQ(specs[0].str(), parse_engine_spec("chain").str());
  EXPECT_EQ(specs[1].get("variant"), "seed2014");
  EXPECT_EQ(specs[1].get("velocity"), "zero");
  EXPECT_EQ(specs[2].get("pos_iters"), "1");
  EXPECT_EQ(parse_engine_list("chain;box2d").size(), 2u);
  EXPECT_THROW(parse_engine_list("chain,,box2d"), InputError);
  EXPECT_THROW(parse_engine_list(""), InputError);
}

}  // namespace
}  // namespace chainbench
