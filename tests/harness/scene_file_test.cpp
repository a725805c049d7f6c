// Scene files: a valid file reads as written; every class of bad input is refused with the file,
// the JSON path and the reason.
#include "scene_file.h"
#include "input_error.h"

#include <gtest/gtest.h>

#include <fstream>
#include <string>

namespace chainbench {
namespace {

// DESIGN.md's example, with every optional key used once.
const char* kValid = R"({
  "schema": 1,
  "name": "push-two",
  "gravity": [0, 0],
  "dt": 0.016666666666666666,
  "steps": 60,
  "rotation": false,
  "friction": 0.0,
  "restitution": 0.0,
  "bodies": [
    {"name": "player", "type": "dynamic", "center": [0, 0], "half_extents": [0.5, 0.5], "mass": 1},
    {"name": "box1",   "type": "dynamic", "center": [1, 0], "half_extents": [0.5, 0.5], "density": 2,
     "friction": 0.3, "restitution": 0.2, "gravity_scale": 0.5, "velocity": [0.1, 0]},
    {"name": "wall",   "type": "static",  "center": [5, 0], "half_extents": [0.5, 2]},
    {"name": "lift",   "type": "kinematic", "center": [0, 3], "half_extents": [2, 0.5], "velocity": [0, -1]}
  ],
  "drivers": [
    {"body": "player", "kind": "velocity", "velocity": [2, 0], "from_step": 0, "to_step": 60}
  ],
  "expect": [
    {"body": "box1", "center": [1.6667, 0], "tolerance": 0.01}
  ]
})";

std::string error_of(const std::string& text) {
  try {
    parse_scene(text, "scene.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "(accepted)";
}

// kValid with `from` replaced by `to`.
std::string edited(const std::string& from, const std::string& to) {
  std::string s = kValid;
  const std::size_t at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) s.replace(at, from.size(), to);
  return s;
}

TEST(SceneFile, ValidFileReadsAsWritten) {
  const Scene s = parse_scene(kValid, "scene.json");
  EXPECT_EQ(s.name, "push-two");
  EXPECT_EQ(s.steps, 60);
  EXPECT_EQ(s.gravity.y, 0.0);
  ASSERT_EQ(s.bodies.size(), 4u);
  EXPECT_EQ(s.bodies[1].mass, 2.0 * 1.0);  // density 2 over a 1 m^2 box
  EXPECT_EQ(*s.bodies[1].friction, 0.3);
  EXPECT_EQ(s.bodies[1].gravity_scale, 0.5);
  EXPECT_EQ(s.bodies[3].kind, BodyKind::kKinematic);
  EXPECT_EQ(s.bodies[3].velocity.y, -1.0);
  ASSERT_EQ(s.drivers.size(), 1u);
  EXPECT_EQ(s.drivers[0].body, 0u);
  EXPECT_EQ(s.drivers[0].to_step, 60);
  ASSERT_EQ(s.expect.size(), 1u);
  EXPECT_EQ(s.expect[0].body, 1u);
}

TEST(SceneFile, OmittedKeysTakeTheDesignDefaults) {
  const Scene s = parse_scene(
      R"({"bodies": [{"type": "static", "center": [0,0], "half_extents": [1,1]}]})", "f");
  EXPECT_EQ(s.gravity.y, -10.0);
  EXPECT_EQ(s.dt, 1.0 / 60.0);
  EXPECT_EQ(s.steps, 120);
  EXPECT_FALSE(s.rotation);
  EXPECT_EQ(s.friction, 0.0);
  EXPECT_EQ(s.bodies[0].name, "body0");
}

struct BadFile {
  const char* name;
  std::string text;
  const char* path;    // the JSON path the message must name
  const char* reason;  // and a piece of its reason
};
void PrintTo(const BadFile& c, std::ostream* os) {
  *os << c.name;
}

class RejectedFile : public ::testing::TestWithParam<BadFile> {};

INSTANTIATE_TEST_SUITE_P(
    Errors, RejectedFile,
    ::testing::Values(
        BadFile{"NotJson", "{\"bodies\": [", "", "not valid JSON"},
        BadFile{"RootNotObject", "[1, 2]", "(root)", "must be an object"},
        BadFile{"UnknownTopKey", edited("\"steps\": 60", "\"step\": 60"), "step", "unknown key"},
        BadFile{"UnknownBodyKey", edited("\"mass\": 1}", "\"mass\": 1, \"colour\": 3}"),
                "bodies[0].colour", "unknown key"},
        BadFile{"UnknownDriverKey", edited("\"from_step\": 0", "\"start\": 0"), "drivers[0].start",
                "unknown key"},
        BadFile{"NumberAsString", edited("\"dt\": 0.016666666666666666", "\"dt\": \"0.016\""), "dt",
                "must be a number, got a string"},
        BadFile{"NaNSpelledAsString", edited("\"mass\": 1}", "\"mass\": \"NaN\"}"),
                "bodies[0].mass", "NaN and infinities"},
        BadFile{"InfinitySpelledAsString", edited("[5, 0]", "[\"Infinity\", 0]"),
                "bodies[2].center[0]", "must be a number"},
        BadFile{"HugeExponent", edited("[1, 0], \"half", "[1e999, 0], \"half"),
                "bodies[1].center[0]", "finite"},
        BadFile{"BooleanForNumber", edited("\"friction\": 0.0", "\"friction\": true"), "friction",
                "got a boolean"},
        BadFile{"ZeroSize", edited("[0.5, 2]", "[0.5, 0]"), "bodies[2].half_extents[1]", "> 0"},
        BadFile{"NegativeSize", edited("[2, 0.5]", "[-2, 0.5]"), "bodies[3].half_extents[0]",
                "> 0"},
        BadFile{"ZeroMass", edited("\"mass\": 1}", "\"mass\": 0}"), "bodies[0].mass", "> 0"},
        BadFile{"NegativeDensity", edited("\"density\": 2", "\"density\": -2"), "bodies[1].density",
                "> 0"},
        BadFile{"MissingMass", edited(", \"mass\": 1}", "}"), "bodies[0].mass", "is required"},
        BadFile{"MassAndDensity", edited("\"mass\": 1}", "\"mass\": 1, \"density\": 1}"),
                "bodies[0].density", "not both"},
        BadFile{"MassOnStatic", edited("[0.5, 2]}", "[0.5, 2], \"mass\": 3}"), "bodies[2].mass",
                "dynamic bodies only"},
        BadFile{"UnknownType", edited("\"type\": \"static\"", "\"type\": \"fixed\""),
                "bodies[2].type", "static, kinematic or dynamic"},
        BadFile{"MissingCenter", edited("\"center\": [5, 0], ", ""), "bodies[2].center",
                "is required"},
        BadFile{"ShortVector", edited("[5, 0]", "[5]"), "bodies[2].center", "two numbers"},
        BadFile{"DuplicateName", edited("\"name\": \"box1\"", "\"name\": \"player\""),
                "bodies[1].name", "already names"},
        BadFile{"DriverOnUnknownBody", edited("{\"body\": \"player\"", "{\"body\": \"ghost\""),
                "drivers[0].body", "no body is named"},
        BadFile{"DriverOnStatic", edited("{\"body\": \"player\"", "{\"body\": \"wall\""),
                "drivers[0].body", "static"},
        BadFile{"DriverKind", edited("\"kind\": \"velocity\"", "\"kind\": \"force\""),
                "drivers[0].kind", "\"velocity\""},
        BadFile{"DriverWindowBackwards",
                edited("\"from_step\": 0, \"to_step\": 60", "\"from_step\": 30, \"to_step\": 10"),
                "drivers[0].to_step", ">= from_step"},
        BadFile{"ExpectUnknownBody",
                edited("{\"body\": \"box1\", \"center\"", "{\"body\": \"box9\", \"center\""),
                "expect[0].body", "no body is named"},
        BadFile{"ExpectZeroTolerance", edited("\"tolerance\": 0.01", "\"tolerance\": 0"),
                "expect[0].tolerance", "> 0"},
        BadFile{"StepsFraction", edited("\"steps\": 60", "\"steps\": 60.5"), "steps",
                "whole number"},
        BadFile{"StepsAbsurd", edited("\"steps\": 60", "\"steps\": 1000000000000"), "steps",
                "must be in"},
        BadFile{"StepsNegative", edited("\"steps\": 60", "\"steps\": -5"), "steps", "must be in"},
        BadFile{"DtZero", edited("\"dt\": 0.016666666666666666", "\"dt\": 0"), "dt", "must be in"},
        BadFile{"GravityHuge", edited("\"gravity\": [0, 0]", "\"gravity\": [0, -1e9]"),
                "gravity[1]", "within"},
        BadFile{"RestitutionAboveOne", edited("\"restitution\": 0.0", "\"restitution\": 1.5"),
                "restitution", "in [0, 1]"},
        BadFile{"FarAway", edited("[0, 3]", "[0, 3e12]"), "bodies[3].center[1]", "within"},
        BadFile{"MovingStatic", edited("[0.5, 2]}", "[0.5, 2], \"velocity\": [1, 0]}"),
                "bodies[2].velocity", "static"},
        BadFile{"BodiesNotArray", R"({"bodies": {"a": 1}})", "bodies", "must be an array"},
        BadFile{"Schema2", edited("\"schema\": 1", "\"schema\": 2"), "schema", "schema 1"}),
    [](const auto& info) { return std::string(info.param.name); });

TEST_P(RejectedFile, NamesFilePathAndReason) {
  const BadFile& bad = GetParam();
  const std::string msg = error_of(bad.text);
  EXPECT_NE(msg.find("scene.json: "), std::string::npos) << msg;
  if (*bad.path) {
    EXPECT_NE(msg.find(std::string(": ") + bad.path + ": "), std::string::npos) << msg;
  }
  EXPECT_NE(msg.find(bad.reason), std::string::npos) << msg;
}

TEST(SceneFile, ReportsEveryProblemNotJustTheFirst) {
  const std::string msg = error_of(edited("\"mass\": 1}", "\"mass\": -1, \"colour\": 3}"));
  EXPECT_NE(msg.find("bodies[0].mass"), std::string::npos) << msg;
  EXPECT_NE(msg.find("bodies[0].colour"), std::string::npos) << msg;
}

TEST(SceneFile, MissingFileIsNamed) {
  try {
    load_scene_file("/nonexistent/dir/scene.json");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/dir/scene.json: cannot open"),
              std::string::npos);
  }
}

TEST(SceneFile, LoadsFromDisk) {
  const std::string path = ::testing::TempDir() + "chainbench_scene_file_test.json";
  std::ofstream(path) << kValid;
  EXPECT_EQ(load_scene_file(path).bodies.size(), 4u);
}

}  // namespace
}  // namespace chainbench
