// SPDX-License-Identifier: MIT
// The expectations that relate bodies (above, below, on, squeezed), no_overlap among named bodies
// and per-body penetration tolerances: each holds on a correct run and fails on a wrong one (a
// state placed by hand where an engine could not be made to fail on purpose), and the scene file
// refuses each malformed form naming the field.
#include "judge/expectations.h"
#include "judge/verdict.h"
#include "run/runner.h"
#include "scenes/scene_file.h"
#include "support/input_error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace chainbench {
namespace {

// Side view: boxes a and b stacked on a floor 12 m wide; a ledge whose top is level with the
// floor's lies 8 m away, so a box on the floor is face to face with it but not over it.
const char* kStack = R"({
  "name": "stack", "steps": 60,
  "bodies": [
    {"name": "floor", "type": "static", "center": [0, -0.5], "half_extents": [6, 0.5]},
    {"name": "ledge", "type": "static", "center": [8, -0.5], "half_extents": [0.5, 0.5]},
    {"name": "a", "type": "dynamic", "center": [0, 0.5], "half_extents": [0.5, 0.5], "mass": 1},
    {"name": "b", "type": "dynamic", "center": [0.2, 1.5], "half_extents": [0.5, 0.5], "mass": 1}
  ],
  "expect": [
    {"body": "b", "above": "a", "tolerance": 0.01, "from_step": 0},
    {"body": "a", "below": "b", "tolerance": 0.01, "from_step": 0},
    {"body": "b", "on": "a", "tolerance": 0.01, "from_step": 0},
    {"body": "a", "on": "floor", "tolerance": 0.01},
    {"body": "a", "above": "floor", "tolerance": 0.01},
    {"body": "a", "on": "ledge", "tolerance": 0.01},
    {"body": "a", "above": "b", "tolerance": 0.01},
    {"body": "b", "below": "a", "tolerance": 0.01},
    {"body": "b", "on": "floor", "tolerance": 0.01}
  ]
})";

EngineRun run(const Scene& s, const char* engine) {
  return run_engine(s, parse_engine_spec(engine), RunOptions{});
}

// The verdict's finding of class c whose detail holds `text`, if any.
bool found(const EngineRun& r, VerdictClass c, const std::string& text = "") {
  if (!r.verdict) return false;
  for (const Finding& f : r.verdict->findings) {
    if (f.what == c && f.detail.find(text) != std::string::npos) return true;
  }
  return false;
}

// Every engine holds the stack still: the first five entries hold, the last four state the
// wrong order or the wrong support and fail by the heights of the boxes.
TEST(ExpectRelations, AStackIsAboveOnAndBelowInEveryEngine) {
  const Scene s = parse_scene(kStack, "stack.json");
  for (const char* engine : {"chain", "chipmunk", "box2d"}) {
    const EngineRun r = run(s, engine);
    ASSERT_TRUE(r.expect) << engine;
    const auto& e = r.expect->entries;
    for (std::size_t i = 0; i < 5; ++i)
      EXPECT_TRUE(e[i].pass) << engine << " entry " << i << " value " << e[i].value;
    // a's bottom face is level with the ledge's top, but a is 7 m short of it along x.
    EXPECT_FALSE(e[5].pass) << engine;
    EXPECT_NEAR(e[5].value, 7.0, 0.02) << engine;
    EXPECT_FALSE(e[6].pass) << engine;  // b's top (2 m) is 2 m above a's bottom (0)
    EXPECT_NEAR(e[6].value, 2.0, 0.02) << engine;
    EXPECT_NEAR(e[6].error, 1.99, 0.02) << engine;
    EXPECT_EQ(*e[6].other, 3u) << engine;
    EXPECT_FALSE(e[7].pass) << engine;
    EXPECT_NEAR(e[7].value, 2.0, 0.02) << engine;
    EXPECT_FALSE(e[8].pass) << engine;  // b's bottom is 1 m over the floor's top
    EXPECT_NEAR(e[8].value, 1.0, 0.02) << engine;
    EXPECT_FALSE(r.expect->pass);
    EXPECT_TRUE(found(r, VerdictClass::kWrong, "expect[6] above a: bottom ")) << engine;
    EXPECT_TRUE(found(r, VerdictClass::kWrong, "expect[5] on a: ")) << engine;
  }
}

// A wrong run, placed by hand: b sunk 0.3 m into a, and slid off it along x.
TEST(ExpectRelations, ABoxSunkIntoAnotherIsNeitherAboveNorOnIt) {
  const Scene s = parse_scene(kStack, "stack.json");
  ExpectationCheck check(s);
  BodyState state(4);
  state.position = {{0, -0.5}, {8, -0.5}, {0, 0.5}, {0, 1.2}};
  check.observe(0, state, nullptr, nullptr);
  state.position[3] = {1.5, 1.5};  // level with a's top, but beside it
  check.observe(1, state, nullptr, nullptr);
  const ExpectResult r = check.result();
  EXPECT_FALSE(r.entries[0].pass);  // above: worst at the sunk state
  EXPECT_EQ(r.entries[0].state, 0);
  EXPECT_NEAR(r.entries[0].value, 0.3, 1e-12);
  EXPECT_NEAR(r.entries[0].error, 0.29, 1e-12);
  EXPECT_FALSE(r.entries[1].pass);  // below: a's top 0.3 m above b's bottom
  EXPECT_NEAR(r.entries[1].value, 0.3, 1e-12);
  // on: sunk 0.3 m, then level with a's top but 0.5 m beyond its edge, which is worse.
  EXPECT_FALSE(r.entries[2].pass);
  EXPECT_EQ(r.entries[2].state, 1);
  EXPECT_NEAR(r.entries[2].value, 0.5, 1e-12);
  EXPECT_NEAR(r.entries[2].error, 0.5, 1e-12);
}

// `on` a body the box is not over along x fails as a miss of its own kind, whatever the faces'
// distance: never a near miss, never "0 m beyond" its tolerance. Placed by hand: b level with a's
// top with their sides only touching (x gap 0), then 0.005 m apart along x.
TEST(ExpectRelations, OnABodyBesideItIsNotOverItAndNoNearMiss) {
  const Scene s = parse_scene(kStack, "stack.json");
  for (const double gap : {0.0, 0.005}) {
    ExpectationCheck check(s);
    BodyState state(4);
    state.position = {{0, -0.5}, {8, -0.5}, {0, 0.5}, {1.0 + gap, 1.5}};
    check.observe(0, state, nullptr, nullptr);
    state.position[3] = {0.2, 1.5};  // then resting on a: the earlier miss stays the worst
    check.observe(1, state, nullptr, nullptr);
    const ExpectResult r = check.result();
    const ExpectOutcome& on = r.entries[2];
    EXPECT_FALSE(on.pass) << gap;
    EXPECT_TRUE(on.beside) << gap;
    EXPECT_EQ(on.state, 0) << gap;
    EXPECT_NEAR(on.value, gap, 1e-12);
    EXPECT_FALSE(on.near) << gap;
    EXPECT_FALSE(r.near_miss) << gap;
    const std::string text = describe(s, on);
    EXPECT_NE(text.find("b: not over a along x ("), std::string::npos) << text;
    EXPECT_NE(text.find(gap > 0 ? "0.005 m beside it" : "their sides only touch"),
              std::string::npos)
        << text;
    EXPECT_EQ(text.find("beyond"), std::string::npos) << text;
  }
}

// Top-down, no gravity: a crate between two static walls touching both sides is squeezed; with
// the right wall 0.3 m off it is not, and with one wall there is no second side at all.
Scene corridor(double right_wall_x, bool right_wall) {
  std::string text = R"({"gravity": [0, 0], "steps": 10, "bodies": [
    {"name": "crate", "type": "dynamic", "center": [0, 0], "half_extents": [0.5, 0.5], "mass": 1},
    {"name": "left", "type": "static", "center": [-1, 0], "half_extents": [0.5, 1]})";
  if (right_wall) {
    text += R"(, {"name": "right", "type": "kinematic", "center": [)" +
            std::to_string(right_wall_x) + R"(, 0], "half_extents": [0.5, 1]})";
  }
  text += R"(], "expect": [{"body": "crate", "squeezed": true, "tolerance": 0.01,
    "from_step": 0}]})";
  return parse_scene(text, "corridor.json");
}

TEST(ExpectRelations, SqueezedNeedsImmovableBodiesOnTwoOppositeSides) {
  const EngineRun held = run(corridor(1.0, true), "chain");
  EXPECT_TRUE(held.expect->pass) << held.expect->entries[0].value;
  const EngineRun loose = run(corridor(1.3, true), "chain");
  ASSERT_FALSE(loose.expect->pass);
  EXPECT_NEAR(loose.expect->entries[0].value, 0.3, 1e-9);
  EXPECT_EQ(*loose.expect->entries[0].other, 2u);  // the right wall, on the looser side
  const EngineRun alone = run(corridor(0.0, false), "chain");
  ASSERT_FALSE(alone.expect->pass);
  EXPECT_FALSE(alone.expect->entries[0].other.has_value());
  EXPECT_TRUE(found(alone, VerdictClass::kWrong,
                    "crate: no static or kinematic body on two opposite sides"));
}

// Side view: a kinematic crusher comes down at 1 m/s onto a player standing on the floor (they
// touch at the start), while a bystander stands 3 m away.
const char* kCrush = R"({
  "name": "crush", "steps": 30,
  "bodies": [
    {"name": "floor", "type": "static", "center": [0, -0.5], "half_extents": [6, 0.5]},
    {"name": "player", "type": "dynamic", "center": [0, 0.5], "half_extents": [0.5, 0.5],
     "mass": 1 PLAYER_TOLERANCE},
    {"name": "crusher", "type": "kinematic", "center": [0, 1.5], "half_extents": [0.5, 0.5],
     "velocity": [0, -1]},
    {"name": "bystander", "type": "dynamic", "center": [3, 0.5], "half_extents": [0.5, 0.5], "mass": 1}
  ],
  "expect": [
    {"body": "player", "squeezed": true, "tolerance": 0.001, "from_step": 1},
    {"no_overlap": 0.001, "bodies": ["crusher", "bystander", "floor"], "from_step": 0},
    {"no_overlap": 0.001, "bodies": ["crusher", "player"], "from_step": 0},
    {"no_overlap": 0.001, "from_step": 0}
  ],
  "penetration_tolerance": 2
})";

Scene crush(const std::string& player_tolerance) {
  std::string text = kCrush;
  const std::string mark = " PLAYER_TOLERANCE";
  text.replace(text.find(mark), mark.size(), player_tolerance);
  return parse_scene(text, "crush.json");
}

// The crusher moves 0.5 m into the space the player fills: the player is squeezed, the crusher
// never reaches the bystander or the floor, and the crusher-player pair (or the player-floor
// pair) overlaps, which a selector naming the crusher and the player catches.
TEST(ExpectRelations, NoOverlapAmongNamedBodiesIgnoresTheSqueezeItMustAllow) {
  const EngineRun r = run(crush(""), "chain");
  const auto& e = r.expect->entries;
  EXPECT_TRUE(e[0].pass) << e[0].value;
  EXPECT_TRUE(e[1].pass) << e[1].value;
  EXPECT_EQ(e[1].value, 0.0);
  EXPECT_FALSE(e[3].pass);  // somewhere the squeeze overlaps
  EXPECT_GT(e[3].value, 0.1);
  // Placed by hand: the crusher 0.3 m into the player, the bystander clear.
  const Scene s = crush("");
  ExpectationCheck check(s);
  BodyState state(4);
  state.position = {{0, -0.5}, {0, 0.5}, {0, 1.2}, {3, 0.5}};
  check.observe(0, state, nullptr, nullptr);
  const ExpectOutcome pair = check.result().entries[2];
  EXPECT_FALSE(pair.pass);
  EXPECT_NEAR(pair.value, 0.3, 1e-12);
  EXPECT_EQ(*pair.body, 1u);
  EXPECT_EQ(*pair.other, 2u);
  EXPECT_TRUE(check.result().entries[1].pass);
}

// The scene allows 2 m for every pair (what a crate squeezed elsewhere might need); the player's
// own 0.05 m makes the crush of the player `penetrating`, as one scene-wide number could not.
TEST(ExpectRelations, APlayersOwnToleranceMakesItsCrushPenetrating) {
  const EngineRun lax = run(crush(""), "chain");
  ASSERT_TRUE(lax.verdict);
  EXPECT_FALSE(found(lax, VerdictClass::kPenetrating)) << lax.verdict->str();
  const EngineRun strict = run(crush(", \"penetration_tolerance\": 0.05"), "chain");
  ASSERT_TRUE(strict.verdict && strict.metrics.worst_overlap);
  EXPECT_TRUE(found(strict, VerdictClass::kPenetrating, "beyond its tolerance 0.05 m"))
      << strict.verdict->str();
  EXPECT_EQ(strict.metrics.worst_overlap->tolerance, 0.05);
}

TEST(ExpectRelations, APairKeepsTheStricterOfItsBodiesTolerances) {
  Scene s = crush(", \"penetration_tolerance\": 0.05");
  EXPECT_EQ(s.pair_penetration_tolerance(1, 2), 0.05);  // the player's
  EXPECT_EQ(s.pair_penetration_tolerance(2, 3), 2.0);   // the scene's
  s.bodies[2].penetration_tolerance = 0.01;
  EXPECT_EQ(s.pair_penetration_tolerance(1, 2), 0.01);  // the smaller of two
  s.penetration_tolerance.reset();
  EXPECT_DOUBLE_EQ(s.pair_penetration_tolerance(0, 3), 0.05);  // 0.1 x 0.5 m
}

std::string error_of(const std::string& text) {
  try {
    parse_scene(text, "f.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "(accepted)";
}

// kStack's bodies with one expect entry, or one body key added to b.
std::string with_entry(const std::string& entry) {
  return std::string(R"({"bodies": [
    {"name": "floor", "type": "static", "center": [0, -0.5], "half_extents": [6, 0.5]},
    {"name": "b", "type": "dynamic", "center": [0, 0.5], "half_extents": [0.5, 0.5], "mass": 1}
  ], "expect": [)") +
         entry + "]}";
}

struct Bad {
  std::string text, message;
};

TEST(ExpectRelations, FileErrorsNameFieldAndReason) {
  const Bad bad[] = {
      {with_entry(R"({"body": "b", "above": "ghost", "tolerance": 0.01})"),
       "f.json: expect[0].above: no body is named \"ghost\""},
      {with_entry(R"({"body": "b", "above": "floor"})"),
       "f.json: expect[0].tolerance: is required with above"},
      {with_entry(R"({"body": "b", "below": "b", "tolerance": 0.01})"),
       "f.json: expect[0].below: names the entry's own body"},
      {with_entry(R"({"body": "*", "on": "floor", "tolerance": 0.01})"),
       "f.json: expect[0].body: \"*\" cannot be on"},
      {with_entry(R"({"on": "floor", "tolerance": 0.01})"),
       "f.json: expect[0].body: is required: the name of a body"},
      {with_entry(R"({"body": "b", "on": 3, "tolerance": 0.01})"),
       "f.json: expect[0].on: must be a string"},
      {with_entry(R"({"body": "b", "on": "floor", "tolerance": 0})"),
       "f.json: expect[0].tolerance: must be > 0"},
      {with_entry(R"({"body": "b", "on": "floor", "above": "floor", "tolerance": 1})"),
       "f.json: expect[0]: states more than one fact"},
      {with_entry(R"({"body": "b", "squeezed": false, "tolerance": 0.01})"),
       "f.json: expect[0].squeezed: must be true"},
      {with_entry(R"({"body": "b", "squeezed": "yes", "tolerance": 0.01})"),
       "f.json: expect[0].squeezed: must be true or false, got a string"},
      {with_entry(R"({"no_overlap": 0, "bodies": ["b"]})"),
       "f.json: expect[0].bodies: must name at least two bodies"},
      {with_entry(R"({"no_overlap": 0, "bodies": ["b", "ghost"]})"),
       "f.json: expect[0].bodies[1]: no body is named \"ghost\""},
      {with_entry(R"({"no_overlap": 0, "bodies": ["b", "b"]})"),
       "f.json: expect[0].bodies[1]: \"b\" is named twice"},
      {with_entry(R"({"no_overlap": 0, "bodies": "b"})"),
       "f.json: expect[0].bodies: must be an array of body names, got a string"},
      {with_entry(R"({"body": "b", "at_rest": 0, "bodies": ["b", "floor"]})"),
       "f.json: expect[0].bodies: belongs to no_overlap"},
      {R"({"bodies": [{"type": "dynamic", "center": [0, 0], "half_extents": [1, 1], "mass": 1,
          "penetration_tolerance": 0}]})",
       "f.json: bodies[0].penetration_tolerance: must be > 0 and <= 1e6 m, got 0"},
      {R"({"bodies": [{"type": "dynamic", "center": [0, 0], "half_extents": [1, 1], "mass": 1,
          "penetration_tolerance": "0.1"}]})",
       "f.json: bodies[0].penetration_tolerance: must be a number, got a string"},
  };
  for (const Bad& b : bad) {
    const std::string msg = error_of(b.text);
    EXPECT_NE(msg.find(b.message), std::string::npos)
        << "wanted: " << b.message << "\ngot: " << msg;
  }
}

// The example file in bench/examples reads, and chain meets every entry it states.
TEST(ExpectRelations, TheCrusherExampleHoldsInChain) {
  const Scene s = load_scene_file(CHAINBENCH_EXAMPLES "/crusher.json");
  const EngineRun r = run(s, "chain");
  ASSERT_TRUE(r.expect);
  for (const ExpectOutcome& o : r.expect->entries)
    EXPECT_TRUE(o.pass) << "expect[" << o.index << "] value " << o.value;
}

}  // namespace
}  // namespace chainbench
