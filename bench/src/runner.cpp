#include "runner.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <ostream>

namespace chainbench {
namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

Timing summarize(std::vector<double>& samples, double setup_ms) {
  Timing t;
  t.setup_ms = setup_ms;
  t.samples = static_cast<int>(samples.size());
  if (samples.empty()) return t;
  std::sort(samples.begin(), samples.end());
  const std::size_t n = samples.size();
  t.median_ms = n % 2 ? samples[n / 2] : 0.5 * (samples[n / 2 - 1] + samples[n / 2]);
  t.mean_ms = std::accumulate(samples.begin(), samples.end(), 0.0) / static_cast<double>(n);
  t.p95_ms = samples[std::min(
      n - 1, static_cast<std::size_t>(std::ceil(0.95 * static_cast<double>(n))) - 1)];
  return t;
}

}  // namespace

std::optional<bool> EngineRun::stable() const {
  if (!metrics.finite) return std::nullopt;
  const bool budget_ok = !chain || chain->budget_hits == 0;
  return *metrics.finite && *metrics.in_bounds && !*metrics.blow_up && budget_ok;
}

TraceWriter::TraceWriter(std::ostream& out) : out_(out) {
  out_ << "engine,step,time,body,x,y,vx,vy,angle,displacement,penetration\n";
}

void TraceWriter::write(const std::string& engine, int step, double time, const BodyState& s,
                        std::span<const double> displacement, std::span<const double> penetration) {
  for (std::size_t i = 0; i < s.position.size(); ++i) {
    out_ << '"' << engine << "\"," << step << ',' << time << ',' << i << ',' << s.position[i].x
         << ',' << s.position[i].y << ',' << s.velocity[i].x << ',' << s.velocity[i].y << ','
         << s.angle[i] << ',' << displacement[i] << ',' << penetration[i] << '\n';
  }
}

EngineRun run_engine(const Scene& scene, const EngineSpec& spec, const RunOptions& options) {
  EngineRun run;
  run.engine = spec.str();
  const auto t0 = Clock::now();
  std::unique_ptr<Engine> engine = make_engine(spec, scene);
  const double setup_ms = ms_since(t0);

  const std::size_t n = scene.bodies.size();
  const bool observe = options.metrics.any() || options.trace != nullptr;
  std::optional<MetricsRecorder> recorder;
  BodyState before(n), after(n);
  if (observe) {
    recorder.emplace(scene, options.metrics);
    engine->read_state(before);
  }
  const chain::StepStats* stats = engine->chain_stats();
  ChainRunStats chain_totals;
  double calls = 0.0, passes = 0.0, contacts = 0.0;

  std::vector<double> samples;
  samples.reserve(static_cast<std::size_t>(scene.steps));
  const int report_every = std::max(1, scene.steps / 100);
  for (int step = 0; step < scene.steps; ++step) {
    if (options.stop && options.stop->load(std::memory_order_relaxed)) {
      run.interrupted = true;
      break;
    }
    const auto s0 = Clock::now();
    engine->step(step);
    const double ms = ms_since(s0);
    if (step > 0) samples.push_back(ms);  // the first step pays for warming caches and buffers
    if (stats) {
      calls += stats->resolve_calls, passes += stats->passes, contacts += stats->contacts;
      chain_totals.max_depth = std::max(chain_totals.max_depth, stats->max_depth);
      chain_totals.budget_hits += stats->budget_hits;
      chain_totals.crush_events += stats->crush_events;
    }
    if (observe) {
      engine->read_state(after);
      recorder->observe(before, after, options.trace != nullptr);
      if (options.trace) {
        options.trace->write(run.engine, step + 1, (step + 1) * scene.dt, after,
                             recorder->step_displacement(), recorder->step_penetration());
      }
      std::swap(before, after);
    }
    if (options.progress && (step + 1) % report_every == 0) options.progress(step + 1, scene.steps);
  }

  BodyState last(n);
  engine->read_state(last);
  run.final_positions = last.position;
  run.final_angles = last.angle;
  run.hash = position_hash(run.final_positions);
  run.timing = summarize(samples, setup_ms);
  if (options.metrics.any()) {
    run.metrics = recorder->result();
    run.metrics_computed = true;
  }
  if (stats) {
    const double steps = static_cast<double>(scene.steps);
    chain_totals.resolve_calls_per_step = calls / steps;
    chain_totals.passes_per_step = passes / steps;
    chain_totals.contacts_per_step = contacts / steps;
    run.chain = chain_totals;
  }
  if (!scene.expect.empty()) {
    ExpectResult r;
    for (const Expectation& e : scene.expect) {
      const Vec2d p = run.final_positions[e.body];
      const double err = std::hypot(p.x - e.center.x, p.y - e.center.y);
      r.max_error = std::isfinite(err) ? std::max(r.max_error, err) : HUGE_VAL;
      if (!(err <= e.tolerance)) r.pass = false;
    }
    run.expect = r;
  }
  return run;
}

}  // namespace chainbench
