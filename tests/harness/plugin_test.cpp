// SPDX-License-Identifier: MIT
// Plugins: a user's resolver in a shared library (chainbench/engine_plugin.h). A ballistic test
// plugin written in C shows that the scene, the drivers and the counters cross the C ABI intact
// (its free fall matches the analytic answer), and one build of it per fault shows that every way
// a plugin can go wrong stops the run with a message naming the plugin and the reason.
#include "campaign/stress.h"
#include "engines/registry.h"
#include "output/trace_writer.h"
#include "run/runner.h"
#include "support/input_error.h"

#include <gtest/gtest.h>

#include <sstream>
#include <string>

namespace chainbench {
namespace {

std::string plugin_spec(const std::string& fault) {
  return "plugin:path=" CHAINBENCH_TEST_PLUGINS "/libtest_plugin_" + fault + ".so";
}

// A ball in free flight, a cart whose x velocity a driver holds at 3 m/s while it falls, and a
// kinematic lift: no two ever touch, so the ballistic plugin's answer is the analytic one.
Scene flight() {
  Scene s;
  s.name = "flight";
  s.steps = 30;
  s.bodies.push_back({"ball", BodyKind::kDynamic, {0, 10}, {0.5, 0.5}, {1, 2}, 2.0, 1.0, {}, {}});
  s.bodies.push_back({"cart", BodyKind::kDynamic, {10, 10}, {0.5, 0.5}, {0, 0}, 1.0, 0.5, {}, {}});
  s.bodies.push_back({"lift", BodyKind::kKinematic, {20, 0}, {1, 0.25}, {0, 1}, 0.0, 1.0, {}, {}});
  Driver d;
  d.body = 1;
  d.velocity = {3, 0};
  d.hold_y = false;
  s.drivers.push_back(d);
  return s;
}

// Semi-implicit Euler from rest-free initial conditions: after n steps the position is
// x0 + n dt v0 + g dt^2 n (n + 1) / 2.
double fallen(double x0, double v0, double g, double dt, int n) {
  return x0 + n * dt * v0 + g * dt * dt * n * (n + 1) / 2.0;
}

TEST(Plugin, BallisticPluginFollowsTheAnalyticFlight) {
  const Scene s = flight();
  const EngineRun run = run_engine(s, parse_engine_spec(plugin_spec("none")), RunOptions{});
  const int n = s.steps;
  ASSERT_EQ(run.final_positions.size(), 3u);
  EXPECT_NEAR(run.final_positions[0].x, 0.0 + n * s.dt * 1.0, 1e-9);
  EXPECT_NEAR(run.final_positions[0].y, fallen(10, 2, -10, s.dt, n), 1e-9);
  EXPECT_NEAR(run.final_positions[1].x, 10.0 + n * s.dt * 3.0, 1e-9);       // x held by its driver
  EXPECT_NEAR(run.final_positions[1].y, fallen(10, 0, -5, s.dt, n), 1e-9);  // gravity scale 0.5
  EXPECT_NEAR(run.final_positions[2].y, 0.0 + n * s.dt * 1.0, 1e-9);
  // Its four counters are each the steps it has taken, aggregated four ways as it declares: the
  // mean over steps (n + 1) / 2, the largest n, the sum n (n + 1) / 2 and the last n.
  ASSERT_EQ(run.counters.size(), 4u);
  EXPECT_EQ(run.counter_defs()[0].name, "steps_so_far");
  EXPECT_EQ(run.counter_defs()[0].help, "steps taken, mean");
  EXPECT_EQ(run.counter_defs()[1].aggregate, Aggregate::kMax);
  EXPECT_EQ(run.counter_defs()[2].aggregate, Aggregate::kSum);
  EXPECT_EQ(run.counter_defs()[3].aggregate, Aggregate::kLast);
  EXPECT_DOUBLE_EQ(run.counters[0], (n + 1) / 2.0);
  EXPECT_DOUBLE_EQ(run.counters[1], n);
  EXPECT_DOUBLE_EQ(run.counters[2], n * (n + 1) / 2.0);
  EXPECT_DOUBLE_EQ(run.counters[3], n);
}

// Every declared key reaches the plugin, in its order, given or defaulted, in canonical form.
TEST(Plugin, SettingsReachThePluginWithDefaultsFilledIn) {
  try {
    run_engine(flight(), parse_engine_spec(plugin_spec("none") + ",label=echo,gain=2.50"),
               RunOptions{});
    FAIL() << "label=echo did not reach the plugin";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("settings: gain=2.5 substeps=1 label=echo"),
              std::string::npos)
        << e.what();
  }
  const EngineSpec spec = parse_engine_spec(plugin_spec("none") + ",substeps=3");
  EXPECT_EQ(spec.get("gain"), "1");
  EXPECT_EQ(spec.get("substeps"), "3");
  EXPECT_EQ(spec.get("label"), "none");
  EXPECT_EQ(spec.label(), "plugin:path=libtest_plugin_none.so,substeps=3");
  EXPECT_EQ(parse_engine_spec(spec.str()), spec);
}

// The world's description carries the scene's step count, every body's name and the drivers
// (body, axes held, velocity, steps), which the describe label makes the plugin echo.
TEST(Plugin, TheDescriptionCarriesNamesDriversAndSteps) {
  Scene s = flight();
  s.drivers[0].from_step = 2;
  s.drivers[0].to_step = 20;
  try {
    run_engine(s, parse_engine_spec(plugin_spec("none") + ",label=describe"), RunOptions{});
    FAIL() << "label=describe did not reach the plugin";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("steps 30, bodies ball cart lift, driver body 1 axes 1 "
                                         "velocity 3 0 steps 2 to 20"),
              std::string::npos)
        << e.what();
  }
  // A driver without an end holds to INT32_MAX.
  try {
    run_engine(flight(), parse_engine_spec(plugin_spec("none") + ",label=describe"), RunOptions{});
    ADD_FAILURE() << "label=describe did not reach the plugin";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("steps 0 to 2147483647"), std::string::npos) << e.what();
  }
}

// Bodies that come and go reach a plugin with CB_CAN_LIFETIMES through add_body and remove_body:
// a ball entering at step 10 falls for the 20 steps it takes part in, from where the scene puts
// it; a cart leaving at step 12 stays where 12 steps took it.
TEST(Plugin, BodiesComeAndGoThroughAddAndRemove) {
  Scene s = flight();
  s.bodies[0].from_step = 10;
  s.bodies[1].to_step = 12;
  s.drivers.clear();
  Expectation left;  // the cart's last state, 12, where 12 steps of its fall took it
  left.kind = Expectation::Kind::kCenter;
  left.body = 1;
  left.center = {10.0, fallen(10, 0, -5, s.dt, 12)};
  left.tolerance = 1e-9;
  left.from_step = 12;
  left.to_step = 12;
  s.expect.push_back(left);
  const EngineRun run = run_engine(s, parse_engine_spec(plugin_spec("none")), RunOptions{});
  ASSERT_FALSE(run.failure);
  ASSERT_EQ(run.final_positions.size(), 3u);
  EXPECT_NEAR(run.final_positions[0].x, 0.0 + 20 * s.dt * 1.0, 1e-9);
  EXPECT_NEAR(run.final_positions[0].y, fallen(10, 2, -10, s.dt, 20), 1e-9);
  ASSERT_TRUE(run.expect.has_value());
  EXPECT_TRUE(run.expect->pass) << run.expect->max_error;
  // Removed, it fell no further: its final entry is not the 30-step fall.
  EXPECT_GT(std::abs(run.final_positions[1].y - fallen(10, 0, -5, s.dt, 30)), 1.0);
  // A plugin that refuses to add a body stops the run naming it.
  try {
    run_engine(s, parse_engine_spec(plugin_spec("add_refused")), RunOptions{});
    FAIL() << "a refused add_body went unnoticed";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("refused to add body ball (add_body returned 1)"),
              std::string::npos)
        << e.what();
  }
}

// A key the plugin does not declare, or a value outside what it declares, is refused when the
// spec is read, naming the spec (so the plugin's library), the key and why.
TEST(Plugin, AnUndeclaredKeyOrABadValueIsRefusedWhenTheSpecIsRead) {
  for (const auto& [keys, message] :
       {std::pair<std::string, std::string>{"colour=red",
                                            "unknown key \"colour\" for plugin (keys: gain, "
                                            "substeps, label)"},
        {"gain=11", "gain: 11 is out of range [0, 10]"},
        {"substeps=2.5", "substeps"},
        {"substeps=9", "substeps"},
        {"label=", "label is empty"}}) {
    SCOPED_TRACE(keys);
    try {
      parse_engine_spec(plugin_spec("none") + "," + keys);
      FAIL() << "accepted";
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(message), std::string::npos) << what;
      EXPECT_NE(what.find("libtest_plugin_none.so"), std::string::npos) << what;
    }
  }
}

TEST(Plugin, ASceneNeedingWhatThePluginLacksIsRefusedByName) {
  Scene s = flight();
  s.bodies[0].friction = 0.5;
  const std::string why = missing_capability(parse_engine_spec(plugin_spec("none")), s);
  EXPECT_NE(why.find("has no friction, and bodies[0] (ball) has friction 0.5"), std::string::npos)
      << why;
  EXPECT_THROW(make_engine(parse_engine_spec(plugin_spec("none")), s), InputError);
}

struct Fault {
  std::string name;
  std::string message;  // what the error must say
};

class PluginFault : public ::testing::TestWithParam<Fault> {};

TEST_P(PluginFault, StopsTheRunWithAMessageNamingThePlugin) {
  const Fault& f = GetParam();
  try {
    run_engine(flight(), parse_engine_spec(plugin_spec(f.name)), RunOptions{});
    FAIL() << "a plugin with fault " << f.name << " ran to the end";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("plugin"), std::string::npos) << what;
    EXPECT_NE(what.find(f.message), std::string::npos) << what;
    // Nothing a plugin hands back reaches a message raw, nor at any length.
    for (const char c : what)
      EXPECT_TRUE(c >= 0x20 && c <= 0x7e) << "byte " << int(c) << " in " << what;
    EXPECT_LT(what.size(), 600u) << what;
  }
}

INSTANTIATE_TEST_SUITE_P(
    EveryFault, PluginFault,
    ::testing::Values(
        Fault{"no_entry", "exports no chainbench_engine_plugin()"},
        Fault{"abi", "built for plugin ABI 3, this chainbench loads ABI 2"},
        Fault{"abi1", "built for plugin ABI 1, this chainbench loads ABI 2: rebuild it"},
        Fault{"key_name",
              "key 0 has no valid name (letters a-z, digits and _, under 32): its "
              "name holds 'G'"},
        // The plugin, its library, the key and the field, each named once, and the reason.
        Fault{"key_default", "plugin ballistic (" CHAINBENCH_TEST_PLUGINS
                             "/libtest_plugin_key_default.so): key gain: its default: 20 is out "
                             "of range [0, 10]"},
        Fault{"key_range", "key substeps: its range [8, 1] is not two whole numbers"},
        Fault{"key_type", "key substeps: its type is 7"},
        Fault{"counter_aggregate", "counter steps_so_far: its aggregate is 9 (CB_AGG_MEAN 0"},
        Fault{"lifetimes_null", "sets CB_CAN_LIFETIMES and leaves remove_body null"},
        Fault{"counter_description",
              "counter steps_so_far: its description holds the non-printable byte 0x0a"},
        Fault{"size", "its cb_engine is"},
        Fault{"null_function", "leaves a required function null"},
        Fault{"bad_counter", "counter 0 has no valid name"},
        Fault{"create", "could not build scene flight: this plugin builds no worlds"},
        Fault{"step", "step 3 failed: the solver diverged"},
        Fault{"count", "its world holds 4 bodies, the scene 3"},
        Fault{"nan", "returned a non-finite state for body ball"},
        Fault{"velocity", "refused to set the velocity of body cart at step 0"},
        // What a hostile plugin hands back: each refused by name, what is echoed
        // cut and printable.
        Fault{"create_unterminated",
              "its message has no terminator within 512 bytes, so it is not shown in "
              "full: \"xxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxx\" "
              "(cut)"},
        Fault{"step_unterminated", "step 3 failed: its message has no terminator"},
        Fault{"name_unterminated",
              "its name has no terminator within 64 bytes (a name is printable "
              "ASCII, under 64 bytes): \"AAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAA"
              "AAAAAAAAAAAAAAAA\" (cut)"},
        Fault{"name_escape", "its name holds the non-printable byte 0x1b at offset 0"},
        Fault{"counter_unterminated",
              "counter 0 has no valid name (letters a-z, digits and _, under 32): "
              "its name has no terminator within 32 bytes"},
        Fault{"counter_duplicate", "counter 1 is named steps_so_far, as an earlier counter is"},
        Fault{"counter_reserved", "its name is reserved for the chain solver's own counter"},
        Fault{"counter_nan", "counter steps_so_far is NaN after step 2"},
        Fault{"step_rc", "step 3 returned 2, which the plugin contract does not"},
        Fault{"capability", "sets capability bits 256 that this chainbench does"},
        Fault{"error_escape",
              "its message holds the non-printable byte 0x1b at offset 3, so it is "
              "not shown in full: \"bad\" (cut)"},
        // A library that dies while it is loaded and checked (in a child process first).
        Fault{"load_crash", "libtest_plugin_load_crash.so: crashed while loading: signal "},
        Fault{"entry_crash", "libtest_plugin_entry_crash.so: crashed while loading: signal "},
        Fault{"name_guard", "libtest_plugin_name_guard.so: crashed while loading: signal "}),
    [](const ::testing::TestParamInfo<Fault>& info) { return info.param.name; });

TEST(Plugin, AMissingFileIsNamed) {
  try {
    parse_engine_spec("plugin:path=/nonexistent/libnothing.so");
    FAIL() << "a missing plugin was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/libnothing.so"), std::string::npos)
        << e.what();
  }
}

// In stress, where every case runs in a child process, a plugin that dies is a crash row like any
// other engine's, and the stress run itself goes on.
TEST(Plugin, APluginThatDiesIsACrashInStress) {
  const StressCase c{"plugin", "stack", {"n=2", "steps=5"}, false};
  const StressVerdict v = run_stress_case(c, parse_engine_spec(plugin_spec("crash")), 60.0);
  EXPECT_FALSE(v.finished);
  EXPECT_EQ(v.verdict(), VerdictClass::kCrash);
  const StressVerdict error = run_stress_case(c, parse_engine_spec(plugin_spec("step")), 60.0);
  EXPECT_EQ(error.verdict(), VerdictClass::kError);
  EXPECT_NE(error.error.find("the solver diverged"), std::string::npos) << error.error;
}

// The example plugin, the relaxation resolver most people write first: a box dropped onto the
// ground comes to rest on it, and its counter reaches the run.
TEST(Plugin, RelaxationExampleRestsABoxOnTheGround) {
  Scene s;
  s.name = "drop";
  s.steps = 120;
  s.bodies.push_back({"ground", BodyKind::kStatic, {0, -0.5}, {10, 0.5}, {}, 0.0, 1.0, {}, {}});
  s.bodies.push_back({"box", BodyKind::kDynamic, {0, 2}, {0.5, 0.5}, {}, 1.0, 1.0, {}, {}});
  const EngineRun run =
      run_engine(s, parse_engine_spec("plugin:path=" CHAINBENCH_RELAXATION_PLUGIN ",iterations=4"),
                 RunOptions{});
  EXPECT_NEAR(run.final_positions[1].x, 0.0, 1e-12);
  // Resting on the ground's top face (y = 0) with its half height 0.5, less at most a step's fall.
  EXPECT_NEAR(run.final_positions[1].y, 0.5, 10.0 / 3600.0);
  EXPECT_TRUE(run.counter("pushes").has_value());
}

}  // namespace
}  // namespace chainbench

namespace chainbench {
namespace {

// In a child process (as run and sweep run a plugin) a run comes back as it is in process: the
// same positions, metrics, expectations and verdict, and every step its observers would have
// seen, to the bit.
TEST(Plugin, ARunInAChildProcessIsTheRunInProcess) {
  Scene s = flight();
  Expectation e;
  e.kind = Expectation::Kind::kCenter;
  e.body = 0;
  e.center = {1.5, 0.0};
  e.tolerance = 0.1;
  s.expect.push_back(e);  // missed: the ball is elsewhere, so the outcome has figures to carry
  const EngineSpec spec = parse_engine_spec(plugin_spec("none"));
  std::ostringstream here_text, child_text;
  TraceWriter here_trace(here_text, s), child_trace(child_text, s);
  RunOptions here;
  here.observers = {&here_trace};
  RunOptions child = here;
  child.observers = {&child_trace};
  child.isolate = true;
  const EngineRun a = run_engine(s, spec, here);
  const EngineRun b = run_engine(s, spec, child);
  ASSERT_FALSE(b.failure) << *b.failure;
  EXPECT_EQ(b.hash, a.hash);
  EXPECT_EQ(b.counters, a.counters);
  EXPECT_EQ(*b.metrics.efd_total, *a.metrics.efd_total);
  EXPECT_EQ(*b.metrics.peak_speed, *a.metrics.peak_speed);
  EXPECT_EQ(b.metrics.escaped, a.metrics.escaped);
  ASSERT_TRUE(b.expect && a.expect);
  EXPECT_FALSE(b.expect->pass);
  EXPECT_EQ(b.expect->max_error, a.expect->max_error);
  EXPECT_EQ(b.verdict->str(), a.verdict->str());
  EXPECT_EQ(child_text.str(), here_text.str());
  EXPECT_GT(child_text.str().size(), 1000u);
}

// A plugin error in the child is the same error here, with its message.
TEST(Plugin, AnErrorInTheChildIsThrownHere) {
  RunOptions child;
  child.isolate = true;
  EXPECT_THROW(
      {
        try {
          run_engine(flight(), parse_engine_spec(plugin_spec("create")), child);
        } catch (const InputError& e) {
          EXPECT_NE(std::string(e.what()).find("this plugin builds no worlds"), std::string::npos)
              << e.what();
          throw;
        }
      },
      InputError);
}

// A crash in the child is the run's crash verdict, with the signal.
TEST(Plugin, ACrashInTheChildIsTheRunsVerdict) {
  RunOptions child;
  child.isolate = true;
  child.timeout_s = 60;
  const EngineRun r = run_engine(flight(), parse_engine_spec(plugin_spec("abort")), child);
  ASSERT_TRUE(r.failure);
  ASSERT_TRUE(r.verdict);
  EXPECT_EQ(r.verdict->worst, VerdictClass::kCrash);
  EXPECT_TRUE(r.final_positions.empty());
}

}  // namespace
}  // namespace chainbench
