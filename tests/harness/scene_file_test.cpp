// SPDX-License-Identifier: MIT
// Scene files: a valid file reads as written; every class of bad input is refused with the file,
// the JSON path and the reason.
#include "scenes/scene_file.h"
#include "support/input_error.h"

#include <gtest/gtest.h>

#include <fstream>
#include <string>

namespace chainbench {
namespace {

// A file with every optional key used once (docs/scene-format.md §1-§5).
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
     "friction": 0.3, "restitution": 0.2, "gravity_scale": 0.5, "velocity": [0.1, 0],
     "category_bits": 4, "mask_bits": 65531},
    {"name": "wall",   "type": "static",  "center": [5, 0], "half_extents": [0.5, 2]},
    {"name": "lift",   "type": "kinematic", "center": [0, 3], "half_extents": [2, 0.5], "velocity": [0, -1]}
  ],
  "drivers": [
    {"body": "player", "kind": "velocity", "velocity": [2, 0], "from_step": 0, "to_step": 60}
  ],
  "expect": [
    {"body": "box1", "center": [1.6667, 0], "tolerance": 0.01},
    {"body": "*", "min": [null, -0.01], "from_step": 0},
    {"body": "player", "max": [4, null], "min": [-1, null]},
    {"body": "box1", "moved": [1.6667, 0], "tolerance": 0.02},
    {"no_overlap": 0.005, "from_step": 10, "to_step": 60},
    {"body": "*", "at_rest": 0.01, "to_step": 5}
  ],
  "penetration_tolerance": 0.02
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

// Every kind of expectation reads as written, windows included.
TEST(SceneFile, ExpectationsReadAsWritten) {
  using Kind = Expectation::Kind;
  const Scene s = parse_scene(kValid, "scene.json");
  ASSERT_EQ(s.expect.size(), 6u);
  const Expectation& center = s.expect[0];
  EXPECT_EQ(center.kind, Kind::kCenter);
  EXPECT_EQ(center.body, 1u);
  EXPECT_EQ(center.center.x, 1.6667);
  EXPECT_EQ(center.tolerance, 0.01);
  EXPECT_FALSE(center.windowed());
  EXPECT_EQ(center.first_state(60), 60);  // the final state only
  const Expectation& floor = s.expect[1];
  EXPECT_EQ(floor.kind, Kind::kBounds);
  EXPECT_EQ(floor.body, Expectation::kEveryDynamic);
  EXPECT_FALSE(floor.min_x.has_value());
  EXPECT_EQ(*floor.min_y, -0.01);
  EXPECT_FALSE(floor.max_x || floor.max_y);
  EXPECT_EQ(floor.first_state(60), 0);
  EXPECT_EQ(floor.last_state(60), 60);  // to the end of the run
  const Expectation& box = s.expect[2];
  EXPECT_EQ(*box.min_x, -1.0);
  EXPECT_EQ(*box.max_x, 4.0);
  EXPECT_EQ(s.expect[3].kind, Kind::kMoved);
  EXPECT_EQ(s.expect[3].moved.x, 1.6667);
  EXPECT_EQ(s.expect[3].tolerance, 0.02);
  const Expectation& overlap = s.expect[4];
  EXPECT_EQ(overlap.kind, Kind::kNoOverlap);
  EXPECT_EQ(overlap.depth, 0.005);
  EXPECT_EQ(overlap.first_state(60), 10);
  EXPECT_EQ(overlap.last_state(60), 60);
  const Expectation& rest = s.expect[5];
  EXPECT_EQ(rest.kind, Kind::kAtRest);
  EXPECT_EQ(rest.speed, 0.01);
  EXPECT_EQ(rest.first_state(60), 0);
  EXPECT_EQ(rest.last_state(60), 5);
  EXPECT_EQ(*s.penetration_tolerance, 0.02);
}

// A scene file run for fewer steps keeps its windowed expectations and drops those stated for
// its own last step; a window the shorter run cannot reach is refused.
TEST(SceneFile, RunLengthDropsFinalStateExpectationsAndChecksWindows) {
  Scene s = parse_scene(edited("\"from_step\": 10, \"to_step\": 60}", "\"from_step\": 10}"),
                        "scene.json");
  const std::string note = set_run_length(s, 30, "scene.json");
  EXPECT_NE(note.find("3 expectation(s) of scene.json"), std::string::npos) << note;
  EXPECT_EQ(s.steps, 30);
  ASSERT_EQ(s.expect.size(), 3u);
  EXPECT_EQ(s.expect[0].last_state(30), 30);
  Scene again = parse_scene(kValid, "scene.json");
  EXPECT_EQ(set_run_length(again, 60, "scene.json"), "");  // its own length: nothing changes
  EXPECT_EQ(again.expect.size(), 6u);
  for (const int steps : {8, 30}) {  // from step 10 fits no 8-step run, to step 60 no 30-step one
    Scene short_run = parse_scene(kValid, "scene.json");
    try {
      set_run_length(short_run, steps, "scene.json");
      FAIL() << steps;
    } catch (const InputError& e) {
      const std::string where = steps == 8 ? "from_step" : "to_step";
      EXPECT_NE(std::string(e.what()).find("scene.json: expect[4]." + where + ": must be in [0, " +
                                           std::to_string(steps) + "]"),
                std::string::npos)
          << e.what();
    }
  }
}

// A final-state entry is dropped by a shorter run whatever it names: its body may not have
// entered by the new last step (here "late" enters at step 30 and the run stops at 20).
TEST(SceneFile, RunLengthDropsAFinalStateEntryOnABodyNotYetThere) {
  Scene s = parse_scene(R"({"schema": 1, "name": "t", "steps": 60, "bodies": [
      {"name": "floor", "type": "static", "center": [0, -0.5], "half_extents": [10, 0.5]},
      {"name": "late", "type": "dynamic", "center": [0, 0.5], "half_extents": [0.5, 0.5],
       "mass": 1, "from_step": 30}],
      "expect": [{"body": "late", "center": [0, 0.5], "tolerance": 0.01}]})",
                        "late.json");
  const std::string note = set_run_length(s, 20, "late.json");
  EXPECT_NE(note.find("1 expectation(s) of late.json"), std::string::npos) << note;
  EXPECT_TRUE(s.expect.empty());
}

// A body that enters only after the run's last step is valid (the file may be run longer) but
// takes part in nothing, and the run says so; run to its step, it does.
TEST(SceneFile, BodiesEnteringAfterTheLastStepAreNoted) {
  Scene s = parse_scene(R"({"schema": 1, "name": "t", "steps": 60, "bodies": [
      {"name": "floor", "type": "static", "center": [0, -0.5], "half_extents": [10, 0.5]},
      {"name": "never", "type": "dynamic", "center": [0, 0.5], "half_extents": [0.5, 0.5],
       "mass": 1, "from_step": 60}]})",
                        "late.json");
  EXPECT_EQ(late_bodies_note(s, "late.json"),
            "1 body of late.json (the first \"never\", from_step 60) enters after the run's last "
            "step, 60, and takes part in nothing");
  set_run_length(s, 80, "late.json");
  EXPECT_EQ(late_bodies_note(s, "late.json"), "");
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
  EXPECT_EQ(s.bodies[1].category_bits, 0x0004);
  EXPECT_EQ(s.bodies[1].mask_bits, 0xFFFB);
  EXPECT_EQ(s.bodies[0].category_bits, 0x0001);  // the defaults: collide with everything
  EXPECT_EQ(s.bodies[0].mask_bits, 0xFFFF);
  EXPECT_TRUE(s.filters());
  EXPECT_FALSE(s.collide(1, 1));
  EXPECT_TRUE(s.collide(0, 1));
  EXPECT_EQ(s.bodies[3].kind, BodyKind::kKinematic);
  EXPECT_EQ(s.bodies[3].velocity.y, -1.0);
  ASSERT_EQ(s.drivers.size(), 1u);
  EXPECT_EQ(s.drivers[0].body, 0u);
  EXPECT_EQ(s.drivers[0].to_step, 60);
  ASSERT_EQ(s.expect.size(), 6u);
  EXPECT_EQ(s.expect[0].body, 1u);
}

// null leaves an axis free: the driver holds x and gravity and contacts keep y.
// A name the reader made up (bodyN for a body without one) that clashes with one the file gives
// says it is a default, whichever comes first.
TEST(SceneFile, ADefaultNameThatClashesSaysItIsADefault) {
  const std::string later = error_of(R"({"bodies": [
    {"name": "body1", "type": "static", "center": [0, 0], "half_extents": [1, 1]},
    {"type": "static", "center": [5, 0], "half_extents": [1, 1]}]})");
  EXPECT_NE(later.find("bodies[1].name: is not given, and its default \"body1\" already names "
                       "bodies[0]: give this body a name"),
            std::string::npos)
      << later;
  const std::string earlier = error_of(R"({"bodies": [
    {"type": "static", "center": [0, 0], "half_extents": [1, 1]},
    {"name": "body0", "type": "static", "center": [5, 0], "half_extents": [1, 1]}]})");
  EXPECT_NE(earlier.find("bodies[1].name: \"body0\" is already the default name of bodies[0], "
                         "which has no name of its own"),
            std::string::npos)
      << earlier;
}

// JSON has one number type: a whole number written as a float is that number, as --steps 1e3
// is; a fraction is still refused (StepsFraction below).
TEST(SceneFile, AWholeNumberWrittenAsAFloatIsThatNumber) {
  EXPECT_EQ(parse_scene(edited("\"steps\": 60", "\"steps\": 1e3"), "scene.json").steps, 1000);
  EXPECT_EQ(parse_scene(edited("\"steps\": 60", "\"steps\": 60.0"), "scene.json").steps, 60);
  const Scene s = parse_scene(edited("\"from_step\": 10", "\"from_step\": 1e1"), "scene.json");
  EXPECT_EQ(s.expect[4].from_step, 10);
}

TEST(SceneFile, DriverWithANullAxisHoldsTheOtherOnly) {
  const Scene s =
      parse_scene(edited("\"velocity\": [2, 0]", "\"velocity\": [2, null]"), "scene.json");
  ASSERT_EQ(s.drivers.size(), 1u);
  EXPECT_TRUE(s.drivers[0].hold_x);
  EXPECT_FALSE(s.drivers[0].hold_y);
  EXPECT_EQ(s.drivers[0].velocity.x, 2.0);
  const Scene both = parse_scene(kValid, "scene.json");
  EXPECT_TRUE(both.drivers[0].hold_x && both.drivers[0].hold_y);
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
        BadFile{"BeltOnADynamicBody",
                edited("\"mass\": 1}", "\"mass\": 1, \"surface_velocity\": [2, 0]}"),
                "bodies[0].surface_velocity", "static and kinematic"},
        BadFile{"BeltAlongY",
                edited("[0.5, 2]}", "[0.5, 2], \"surface_velocity\": [2, 1]}"),
                "bodies[2].surface_velocity[1]", "must be 0"},
        BadFile{"CategoryPast16Bits",
                edited("\"mass\": 1}", "\"mass\": 1, \"category_bits\": 65536}"),
                "bodies[0].category_bits", "65535"},
        BadFile{"MaskNegative", edited("\"mass\": 1}", "\"mass\": 1, \"mask_bits\": -1}"),
                "bodies[0].mask_bits", "0"},
        BadFile{"MaskNotWhole", edited("\"mass\": 1}", "\"mask_bits\": 1.5, \"mass\": 1}"),
                "bodies[0].mask_bits", "whole"},
        BadFile{"CategoryAsString",
                edited("\"mass\": 1}", "\"mass\": 1, \"category_bits\": \"0x2\"}"),
                "bodies[0].category_bits", "string"},
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
        BadFile{"DriverHoldsNoAxis", edited("\"velocity\": [2, 0]", "\"velocity\": [null, null]"),
                "drivers[0].velocity", "holds neither axis"},
        BadFile{"DriverAxisNotANumber",
                edited("\"velocity\": [2, 0]", "\"velocity\": [\"fast\", null]"),
                "drivers[0].velocity[0]", "must be a number"},
        BadFile{"DriverVelocityShort", edited("\"velocity\": [2, 0]", "\"velocity\": [2]"),
                "drivers[0].velocity", "null for a free axis"},
        BadFile{"DriverWindowBackwards",
                edited("\"from_step\": 0, \"to_step\": 60", "\"from_step\": 30, \"to_step\": 10"),
                "drivers[0].to_step", ">= from_step"},
        BadFile{"ExpectUnknownBody",
                edited("{\"body\": \"box1\", \"center\"", "{\"body\": \"box9\", \"center\""),
                "expect[0].body", "no body is named"},
        BadFile{"ExpectZeroTolerance", edited("\"tolerance\": 0.01", "\"tolerance\": 0"),
                "expect[0].tolerance", "> 0"},
        BadFile{"ExpectUnknownKey", edited("\"at_rest\": 0.01", "\"at_rest\": 0.01, \"speed\": 1"),
                "expect[5].speed", "unknown key"},
        BadFile{"ExpectNothing", edited("{\"no_overlap\": 0.005, ", "{"), "expect[4]",
                "states nothing"},
        BadFile{"ExpectTwoFacts", edited("\"at_rest\": 0.01", "\"at_rest\": 0.01, \"max\": [1, 1]"),
                "expect[5]", "more than one fact"},
        BadFile{"ExpectBoundNoAxis", edited("\"min\": [null, -0.01]", "\"min\": [null, null]"),
                "expect[1]", "bound no axis"},
        BadFile{"ExpectMinAboveMax", edited("\"max\": [4, null]", "\"max\": [-2, null]"),
                "expect[2].min[0]", "x min -1 is above x max -2"},
        BadFile{"ExpectBoundNotPair", edited("\"min\": [null, -0.01]", "\"min\": -0.01"),
                "expect[1].min", "two numbers or nulls"},
        BadFile{"ExpectBoundString", edited("\"min\": [null, -0.01]", "\"min\": [null, \"low\"]"),
                "expect[1].min[1]", "must be a number"},
        BadFile{
            "ExpectWindowBeyondSteps",
            edited("\"from_step\": 10, \"to_step\": 60}", "\"from_step\": 10, \"to_step\": 61}"),
            "expect[4].to_step", "must be in [0, 60]"},
        BadFile{
            "ExpectWindowBackwards",
            edited("\"from_step\": 10, \"to_step\": 60}", "\"from_step\": 40, \"to_step\": 20}"),
            "expect[4].to_step", "must be >= from_step"},
        BadFile{"ExpectWindowNegative", edited("\"from_step\": 10", "\"from_step\": -1"),
                "expect[4].from_step", "must be in"},
        BadFile{"ExpectEveryWithCenter",
                edited("{\"body\": \"box1\", \"center\"", "{\"body\": \"*\", \"center\""),
                "expect[0].body", "cannot have one expected centre"},
        BadFile{"ExpectNoOverlapWithBody",
                edited("{\"no_overlap\": 0.005", "{\"body\": \"box1\", \"no_overlap\": 0.005"),
                "expect[4].body", "every pair"},
        BadFile{"ExpectNoOverlapNegative", edited("\"no_overlap\": 0.005", "\"no_overlap\": -1"),
                "expect[4].no_overlap", "in [0, 1e6]"},
        BadFile{"ExpectAtRestNegative", edited("\"at_rest\": 0.01", "\"at_rest\": -0.5"),
                "expect[5].at_rest", "in [0, 1e5]"},
        BadFile{"ExpectAtRestWithoutBody", edited("{\"body\": \"*\", \"at_rest\"", "{\"at_rest\""),
                "expect[5].body", "is required"},
        BadFile{"ExpectToleranceWithoutCenter",
                edited("\"at_rest\": 0.01", "\"at_rest\": 0.01, \"tolerance\": 1"),
                "expect[5].tolerance", "belongs to center and moved"},
        BadFile{"ExpectMovedWithoutTolerance",
                edited("\"moved\": [1.6667, 0], \"tolerance\": 0.02", "\"moved\": [1.6667, 0]"),
                "expect[3].tolerance", "is required with moved"},
        BadFile{"DuplicateKey", edited("\"steps\": 60,", "\"steps\": 60, \"steps\": 61,"), "steps",
                "is given twice"},
        BadFile{"BodyNamedStar", edited("\"name\": \"wall\"", "\"name\": \"*\""), "bodies[2].name",
                "kept for \"every dynamic body\""},
        BadFile{"ExpectWindowHuge",
                edited("\"from_step\": 10", "\"from_step\": 99999999999999999999"),
                "expect[4].from_step", "must be in [0, 10000000], got 1e+20"},
        BadFile{"PenetrationToleranceZero",
                edited("\"penetration_tolerance\": 0.02", "\"penetration_tolerance\": 0"),
                "penetration_tolerance", "> 0"},
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

// "*" means every dynamic body: a scene without any cannot use it.
TEST(SceneFile, EveryDynamicBodyNeedsOne) {
  const std::string msg = error_of(R"({"bodies": [{"type": "static", "center": [0, 0],
    "half_extents": [1, 1]}], "expect": [{"body": "*", "at_rest": 0.1}]})");
  EXPECT_NE(msg.find("expect[0].body: \"*\" names every dynamic body, and the scene has none"),
            std::string::npos)
      << msg;
}

TEST(SceneFile, ReportsEveryProblemNotJustTheFirst) {
  const std::string msg = error_of(edited("\"mass\": 1}", "\"mass\": -1, \"colour\": 3}"));
  EXPECT_NE(msg.find("bodies[0].mass"), std::string::npos) << msg;
  EXPECT_NE(msg.find("bodies[0].colour"), std::string::npos) << msg;
}

TEST(SceneFile, MissingFileOrDirectoryIsNamed) {
  for (const auto& [path, why] :
       {std::pair<std::string, std::string>{"/nonexistent/dir/scene.json", ": no such file"},
        {::testing::TempDir(), ": is a directory, not a scene file"}}) {
    try {
      load_scene_file(path);
      FAIL() << path;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(path + why), std::string::npos) << e.what();
    }
  }
}

TEST(SceneFile, LoadsFromDisk) {
  const std::string path = ::testing::TempDir() + "chainbench_scene_file_test.json";
  std::ofstream(path) << kValid;
  EXPECT_EQ(load_scene_file(path).bodies.size(), 4u);
}

}  // namespace
}  // namespace chainbench
