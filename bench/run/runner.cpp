// SPDX-License-Identifier: MIT
#include "run/runner.h"

#include "run/isolated_run.h"
#include "run/lifetimes.h"
#include "run/state_feed.h"
#include "support/input_error.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <utility>

namespace chainbench {
namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

// Sums an engine's stage times over the timed steps (the first step's apart, as its time is).
class StageSums {
 public:
  void first(std::span<const StageTime> stages) { first_.assign(stages.begin(), stages.end()); }
  void add(std::span<const StageTime> stages) {
    if (sums_.empty()) {
      for (const StageTime& s : stages)
        sums_.push_back({s.name, 0.0});
    }
    for (std::size_t i = 0; i < stages.size() && i < sums_.size(); ++i)
      sums_[i].ms += stages[i].ms;
    ++steps_;
  }
  // Means over the timed steps, or the first step's times when it was the only one.
  std::vector<StageMean> means() const {
    if (steps_ == 0) {
      std::vector<StageMean> out;
      for (const StageTime& s : first_)
        out.push_back({s.name, s.ms});
      return out;
    }
    std::vector<StageMean> out = sums_;
    for (StageMean& s : out)
      s.ms /= static_cast<double>(steps_);
    return out;
  }

 private:
  std::vector<StageTime> first_;
  std::vector<StageMean> sums_;
  int steps_ = 0;
};

}  // namespace

Timing summarize_steps(std::vector<double> samples, double setup_ms) {
  Timing t;
  t.setup_ms = setup_ms;
  t.samples = static_cast<int>(samples.size());
  if (samples.empty()) return t;
  std::sort(samples.begin(), samples.end());
  const std::size_t n = samples.size();
  t.median_ms = n % 2 ? samples[n / 2] : 0.5 * (samples[n / 2 - 1] + samples[n / 2]);
  t.mean_ms = std::accumulate(samples.begin(), samples.end(), 0.0) / static_cast<double>(n);
  auto quantile = [&](double q) {
    return samples[std::min(n - 1, static_cast<std::size_t>(q * static_cast<double>(n - 1) + 0.5))];
  };
  t.spread_ms = 0.5 * (quantile(0.75) - quantile(0.25));
  auto nearest_rank = [&](double q) {
    const auto rank = static_cast<std::size_t>(std::ceil(q * static_cast<double>(n)));
    return samples[std::min(n, std::max<std::size_t>(rank, 1)) - 1];
  };
  t.p95_ms = nearest_rank(0.95);
  t.p99_ms = nearest_rank(0.99);
  t.max_ms = samples.back();
  return t;
}

EngineRun run_engine(const Scene& scene, const EngineSpec& spec, const RunOptions& options) {
  if (options.isolate && engine_def(spec.engine).isolated)
    return run_engine_in_child(scene, spec, options);
  EngineRun run;
  run.spec = spec;
  run.engine = spec.str();
  const auto t0 = Clock::now();
  std::unique_ptr<Engine> engine = make_engine(spec, scene);
  const double setup_ms = ms_since(t0);

  const std::size_t n = scene.bodies.size();
  const Lifetimes lives(scene);
  // Metrics and traces look at every step; expectations only at the states they name. Each sees
  // a body only while it is in the world (presence.h).
  const bool observed = !options.observers.empty();
  const MetricSelection metrics = options.metrics;
  const bool every_step = metrics.any() || observed;
  ExpectationCheck expect(scene);
  std::optional<MetricsRecorder> recorder;
  if (every_step) recorder.emplace(scene, metrics);
  StateFeed feed(*engine, n);
  int before_state = -1;  // the state last read (feed.before() after the next read), -1: none
  auto check = [&](int k, const BodyState& state, const PairOverlap* deepest) {
    const BodyState* previous = before_state == k - 1 ? &feed.before() : nullptr;
    expect.observe(k, state, previous, deepest);
  };
  if (every_step || expect.needs_state(0)) {
    feed.read();
    before_state = 0;
    if (!expect.empty() && expect.needs_state(0)) {
      const PairOverlap deepest = MetricsRecorder::deepest_overlap(scene, feed.after(), 0);
      expect.observe(0, feed.after(), nullptr, expect.needs_depth(0) ? &deepest : nullptr);
    }
  }
  const std::span<const CounterDef> engine_counters = engine->counter_defs();
  run.defs.assign(engine_counters.begin(), engine_counters.end());
  const std::vector<CounterDef>& counter_defs = run.defs;
  for (StepObserver* o : options.observers)
    o->begin(spec, counter_defs);
  std::vector<double> totals(counter_defs.size(), 0.0);
  int steps_taken = 0;
  if (options.stages) engine->measure_stages();
  StageSums stage_sums;

  std::vector<double> samples;
  samples.reserve(static_cast<std::size_t>(scene.steps));
  double first_ms = 0.0;
  const int report_every = std::max(1, scene.steps / 100);
  for (int step = 0; step < scene.steps; ++step) {
    if (options.stop && options.stop->load(std::memory_order_relaxed)) {
      run.interrupted = true;
      break;
    }
    if (options.step_mark) options.step_mark->store(step + 1, std::memory_order_relaxed);
    const auto s0 = Clock::now();
    // Bodies leave before their to_step and enter after the step before their from_step, so
    // that state from_step shows them as the scene describes them; both in the step's time.
    lives.leave(*engine, step);
    engine->step(step);
    lives.enter(*engine, step + 1);
    const double ms = ms_since(s0);
    // The first step pays for warming caches and buffers: timed apart, and counted only when the
    // run has no other (a cold figure says more than none).
    if (step > 0) {
      samples.push_back(ms);
      if (options.stages) stage_sums.add(engine->stages());
    } else {
      first_ms = ms;
      if (options.stages) stage_sums.first(engine->stages());
    }
    ++steps_taken;
    const bool degraded = engine->degraded();
    run.degraded_steps += degraded;
    if (!totals.empty()) {
      const std::span<const double> values = engine->counters();
      for (std::size_t c = 0; c < totals.size() && c < values.size(); ++c) {
        totals[c] = aggregate_step(counter_defs[c].aggregate, totals[c], values[c]);
      }
    }
    const int k = step + 1;  // the state after this step
    if (every_step || expect.needs_state(k)) {
      feed.read();
      const BodyState& after = feed.after();
      const bool depth = expect.needs_depth(k);
      if (recorder) {
        recorder->observe(feed.before(), after, k, observed, depth, feed.changed());
        if (observed) {
          StepView view;
          view.step = k;
          view.time = k * scene.dt;
          view.state = &after;
          view.displacement = recorder->step_displacement();
          view.penetration = recorder->step_penetration();
          if (lives.any()) view.present = recorder->presence().mask();
          view.counters = engine->counters();
          view.events = engine->events();
          view.degraded = degraded;
          view.ms = ms;
          for (StepObserver* o : options.observers)
            o->observe(view);
        }
        if (expect.needs_state(k)) check(k, after, depth ? &recorder->last_deepest() : nullptr);
      } else {
        const PairOverlap deepest =
            depth ? MetricsRecorder::deepest_overlap(scene, after, k) : PairOverlap{};
        check(k, after, depth ? &deepest : nullptr);
      }
      before_state = k;
    }
    if (options.progress && k % report_every == 0) options.progress(k, scene.steps);
  }

  BodyState last(n);
  engine->read_state(last);
  run.final_positions = last.position;
  run.final_angles = last.angle;
  run.final_state = steps_taken;
  run.hash = position_hash(run.final_positions);
  if (samples.empty() && steps_taken > 0) samples.push_back(first_ms);
  run.stages = stage_sums.means();
  run.timing = summarize_steps(std::move(samples), setup_ms);
  if (metrics.any()) {
    run.metrics = recorder->result(last);
    run.metrics_computed = true;
  }
  for (std::size_t c = 0; c < totals.size(); ++c) {
    if (counter_defs[c].aggregate == Aggregate::kMean) totals[c] /= std::max(1, steps_taken);
  }
  run.counters = std::move(totals);
  if (!expect.empty()) run.expect = expect.result();
  run.verdict = judge(scene, run.metrics, run.expect, run.degraded_steps);
  return run;
}

}  // namespace chainbench
