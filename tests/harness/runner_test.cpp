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

TEST(Runner, ChainStatisticsOnlyForTheChainEngine) {
  const Scene s = make_scene("push_into_wall", {"steps=30"});
  const EngineRun chain_run = run_engine(s, parse_engine_spec("chain"), RunOptions{});
  ASSERT_TRUE(chain_run.chain.has_value());
  EXPECT_GT(chain_run.chain->resolve_calls_per_step, 10.0);  // the push reaches the wall each step
  EXPECT_GE(chain_run.chain->max_depth, 11u);
  EXPECT_EQ(chain_run.chain->budget_hits, 0u);
  EXPECT_FALSE(run_engine(s, parse_engine_spec("box2d"), RunOptions{}).chain.has_value());
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

TEST(Runner, TraceHasARowPerBodyPerStep) {
  const Scene s = make_scene("squeeze", {"steps=5"});
  std::ostringstream out;
  TraceWriter trace(out);
  RunOptions options;
  options.trace = &trace;
  run_engine(s, parse_engine_spec("chain"), options);
  std::istringstream in(out.str());
  std::string line;
  int rows = -1;  // the header
  while (std::getline(in, line))
    ++rows;
  EXPECT_EQ(rows, 5 * 3);
  EXPECT_EQ(out.str().rfind("engine,step,time,body,x,y,vx,vy,angle,displacement,penetration\n", 0),
            0u);
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
