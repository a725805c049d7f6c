// SPDX-License-Identifier: MIT
// The runner: timing samples, metrics only when asked, chain statistics, expectations, traces.
#include "run/runner.h"
#include "output/trace_writer.h"
#include "scenes/scene_library.h"

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
  EXPECT_LE(r.timing.p95_ms, r.timing.p99_ms);
  EXPECT_LE(r.timing.p99_ms, r.timing.max_ms);
}

// The worst frame: p99 by nearest rank and the slowest step. Of 200 steps, 197 of 1 ms and one
// each of 1.5, 2 and 9 ms: p95 (rank 190) hides them all, p99 is rank 198 (1.5 ms), max 9 ms.
TEST(Runner, StepTimesGiveP99AndTheSlowestStep) {
  std::vector<double> samples(200, 1.0);
  samples[17] = 9.0;
  samples[120] = 2.0;
  samples[5] = 1.5;
  const Timing t = summarize_steps(samples, 0.0);
  EXPECT_EQ(t.median_ms, 1.0);
  EXPECT_EQ(t.p95_ms, 1.0);
  EXPECT_EQ(t.p99_ms, 1.5);  // rank ceil(0.99 * 200) = 198: 1.5 < 2 < 9 above it
  EXPECT_EQ(t.max_ms, 9.0);
  const Timing one = summarize_steps({4.0}, 0.0);
  EXPECT_EQ(one.p99_ms, 4.0);
  EXPECT_EQ(one.max_ms, 4.0);
  const Timing none = summarize_steps({}, 0.0);
  EXPECT_EQ(none.max_ms, 0.0);
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

// A row per body at step 1, then a row only where something changed; the engine by its label,
// the body by its name, the engine's full spec once on a comment line before its rows.
TEST(Runner, TraceWritesChangedRowsOnlyAndTheSpecOnce) {
  const Scene s = make_scene("push_into_wall", {"n=3", "steps=5"});
  std::ostringstream out;
  TraceWriter trace(out, s, TraceFormat::kSparse);
  RunOptions options;
  options.observers.push_back(&trace);
  run_engine(s, parse_engine_spec("chain:velocity=zero"), options);
  std::istringstream in(out.str());
  std::vector<std::string> rows, comments;
  std::string header;
  std::getline(in, header);
  EXPECT_EQ(header, "engine,step,body,x,y,vx,vy,angle,displacement,penetration");
  for (std::string line; std::getline(in, line);)
    (line.rfind('#', 0) == 0 ? comments : rows).push_back(line);
  ASSERT_EQ(comments.size(), 4u);
  EXPECT_EQ(comments[1], "# dt 0.016666666666666666 s (time = step * dt)");
  EXPECT_EQ(comments[2].rfind("# steps 5 ", 0), 0u) << comments[2];
  EXPECT_EQ(comments[3],
            "# engine chain:velocity=zero = " + parse_engine_spec("chain:velocity=zero").str());
  // Step 1: all five bodies (pusher, three boxes, wall). Against the wall the boxes never move;
  // the driven pusher creeps by rounding (1e-17 m a step), so only its row comes back.
  ASSERT_EQ(rows.size(), s.bodies.size() + 4) << out.str();
  EXPECT_EQ(rows[0].rfind("chain:velocity=zero,1,pusher,", 0), 0u) << rows[0];
  EXPECT_EQ(rows[4].rfind("chain:velocity=zero,1,wall,", 0), 0u) << rows[4];
  for (int step = 2; step <= 5; ++step) {
    const std::string& row = rows[s.bodies.size() + step - 2];
    EXPECT_EQ(row.rfind("chain:velocity=zero," + std::to_string(step) + ",pusher,", 0), 0u) << row;
  }
}

// A moving body has a row every step, with every digit of its position.
TEST(Runner, TraceWritesEveryStepOfAMovingBodyInFullPrecision) {
  const Scene s = make_scene("push_row", {"n=2", "steps=4"});
  std::ostringstream out;
  TraceWriter trace(out, s, TraceFormat::kSparse);
  RunOptions options;
  options.observers.push_back(&trace);
  const EngineRun run = run_engine(s, parse_engine_spec("chain"), options);
  std::istringstream in(out.str());
  std::vector<std::string> last_row(s.bodies.size());
  int rows = 0;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("chain,", 0) != 0) continue;
    ++rows;
    for (std::size_t i = 0; i < s.bodies.size(); ++i) {
      if (line.find("," + s.bodies[i].name + ",") != std::string::npos) last_row[i] = line;
    }
  }
  EXPECT_EQ(rows, 4 * 3);  // the pusher and both boxes move in every step
  for (std::size_t i = 0; i < s.bodies.size(); ++i) {
    // step,body,x: the x after "chain,4,NAME,"
    const std::string& row = last_row[i];
    const std::size_t at = ("chain,4," + s.bodies[i].name + ",").size();
    ASSERT_EQ(row.rfind("chain,4," + s.bodies[i].name + ",", 0), 0u) << row;
    EXPECT_EQ(std::stod(row.substr(at)), run.final_positions[i].x) << row;
  }
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
