// The runner: timing samples, metrics only when asked, chain statistics, expectations, traces.
#include "runner.h"
#include "scene_library.h"

#include <gtest/gtest.h>

#include <sstream>

namespace chainbench {
namespace {

TEST(Runner, BareRunTimesEveryStepButTheFirstAndComputesNoMetric) {
  const Scene s = make_scene("push_row", {"steps=40"});
  RunOptions options;
  options.metrics = MetricSelection::none();
  const EngineRun r = run_engine(s, parse_engine_spec("chain"), options);
  EXPECT_EQ(r.timing.samples, 39);
  EXPECT_FALSE(r.metrics_computed);
  EXPECT_FALSE(r.metrics.efd_total || r.metrics.max_penetration || r.metrics.finite);
  EXPECT_FALSE(r.stable().has_value());
  EXPECT_EQ(r.final_positions.size(), s.bodies.size());
  EXPECT_EQ(r.hash, position_hash(r.final_positions));
  EXPECT_LE(r.timing.median_ms, r.timing.p95_ms);
}

// Each engine's counters are aggregated as it declares them: per-step means, sums and maxima.
TEST(Runner, CountersAreAggregatedAsTheirEngineDeclares) {
  const Scene s = make_scene("push_into_wall", {"steps=30"});
  const EngineRun chain_run = run_engine(s, parse_engine_spec("chain"), RunOptions{});
  ASSERT_EQ(chain_run.counters.size(), chain_run.counter_defs().size());
  EXPECT_GT(*chain_run.counter("resolve_calls"), 10.0);  // the push reaches the wall each step
  EXPECT_GE(*chain_run.counter("max_depth"), 11.0);
  EXPECT_EQ(*chain_run.counter("budget_hits"), 0.0);
  EXPECT_EQ(chain_run.degraded_steps, 0u);
  const EngineRun box2d = run_engine(s, parse_engine_spec("box2d"), RunOptions{});
  EXPECT_FALSE(box2d.counter("resolve_calls").has_value());
  // The row of ten touches itself and the wall: 11 contacts after every step.
  EXPECT_NEAR(*box2d.counter("contacts"), 11.0, 0.5);
}

TEST(Runner, ExpectationsPassOrFailPerEngine) {
  Scene s = make_scene("push_row", {"n=2", "steps=60"});
  // Zero rule: all three move speed * t / 3 = 2 * 1 / 3 m. Inelastic: the row is carried at
  // speed sooner, so it ends further on.
  Expectation e;
  e.body = 2;
  e.center = {2.0 + 2.0 / 3.0, 0.0};
  e.tolerance = 1e-6;
  s.expect = {e};
  const EngineRun zero = run_engine(s, parse_engine_spec("chain:velocity=zero"), RunOptions{});
  ASSERT_TRUE(zero.expect.has_value());
  EXPECT_TRUE(zero.expect->pass) << zero.expect->max_error;
  const EngineRun inelastic = run_engine(s, parse_engine_spec("chain"), RunOptions{});
  EXPECT_FALSE(inelastic.expect->pass);
  EXPECT_GT(inelastic.expect->max_error, 0.1);
}

// A row per body per step, the engine by its label and the body by its name, and the engine's
// full spec once, on a comment line before its rows.
TEST(Runner, TraceHasARowPerBodyPerStepAndTheSpecOnce) {
  const Scene s = make_scene("squeeze", {"steps=5"});
  std::ostringstream out;
  TraceWriter trace(out, s);
  RunOptions options;
  options.trace = &trace;
  run_engine(s, parse_engine_spec("chain:velocity=zero"), options);
  std::istringstream in(out.str());
  std::string line;
  std::vector<std::string> lines;
  while (std::getline(in, line))
    lines.push_back(line);
  ASSERT_EQ(lines.size(), 2u + 5 * 3);  // header, spec, 5 steps of 3 bodies
  EXPECT_EQ(lines[0], "engine,step,time,body,x,y,vx,vy,angle,displacement,penetration");
  EXPECT_EQ(lines[1],
            "# engine chain:velocity=zero = " + parse_engine_spec("chain:velocity=zero").str());
  EXPECT_EQ(lines[2].rfind("\"chain:velocity=zero\",1,", 0), 0u) << lines[2];
  EXPECT_NE(lines[3].find(",\"box\","), std::string::npos) << lines[3];  // body 1, by name
}

TEST(Runner, SameSceneSameEngineSameBits) {
  const Scene s = make_scene("pyramid", {"base=8", "steps=60"});
  for (const char* spec : {"chain", "chain:variant=seed2014", "box2d"}) {
    const EngineRun a = run_engine(s, parse_engine_spec(spec), RunOptions{});
    const EngineRun b = run_engine(s, parse_engine_spec(spec), RunOptions{});
    EXPECT_EQ(a.hash, b.hash) << spec;
  }
}

}  // namespace
}  // namespace chainbench
