// SPDX-License-Identifier: MIT
#include "campaign/sweep.h"

#include "judge/metric_table.h"
#include "output/report.h"
#include "output/trace_writer.h"
#include "support/input_error.h"
#include "support/text_table.h"

#include <algorithm>
#include <cmath>

namespace chainbench {
namespace {

// The error of a point against the scene's expectations: the largest of its entries' errors
// (distance from an expected centre, or how far beyond a bound or overlap limit), and the root mean
// square over every body each entry names. Rest limits, in m/s, count in the verdict only.
PositionError expectation_error(const Scene& scene, const ExpectResult& r) {
  PositionError e;
  double sum = 0.0, count = 0.0;
  for (const ExpectOutcome& o : r.entries) {
    if (scene.expect[o.index].kind == Expectation::Kind::kAtRest) continue;  // a speed, not metres
    if (!std::isfinite(o.error) || !std::isfinite(o.rms)) return {HUGE_VAL, HUGE_VAL};
    e.max = std::max(e.max, o.error);
    sum += o.rms * o.rms * static_cast<double>(o.bodies);
    count += static_cast<double>(o.bodies);
  }
  e.rms = count > 0.0 ? std::sqrt(sum / count) : 0.0;
  return e;
}

}  // namespace

SweepResult sweep(const Scene& scene, const std::vector<EngineSpec>& grid,
                  const EngineSpec& reference, const SweepOptions& options) {
  SweepResult result;
  result.scene = scene.name;
  result.bodies = static_cast<int>(scene.bodies.size());
  result.steps = scene.steps;
  RunOptions run_options;  // every metric
  run_options.stop = options.stop;
  run_options.isolate = true;  // a plugin that dies is its point's crash row
  run_options.timeout_s = options.timeout_s;
  const bool use_expect = !scene.expect.empty();
  auto included = [&](std::size_t j) { return options.include.empty() || options.include[j]; };
  const int points =
      static_cast<int>(std::count_if(grid.begin(), grid.end(), [&](const EngineSpec& spec) {
        return included(static_cast<std::size_t>(&spec - grid.data()));
      }));
  const int total = points + (use_expect ? 0 : 1);
  int done = 0;
  auto stopped = [&] { return options.stop && options.stop->load(); };
  auto report = [&](const std::string& label) {
    if (options.progress) options.progress(label, done, total);
  };
  if (use_expect) {
    result.reference = "expect";
  } else if (points == 0) {
    result.reference = reference.str();  // nothing to measure here: the reference need not run
    result.reference_label = reference.label();
  } else {
    result.reference = reference.str();
    result.reference_label = reference.label();
    report("reference " + reference.label());
    result.reference_run = run_engine(scene, reference, run_options);
    ++done;
    if (result.reference_run->interrupted) {
      result.interrupted = true;
      return result;
    }
  }
  for (const EngineSpec& spec : grid) {
    if (!included(static_cast<std::size_t>(&spec - grid.data()))) continue;
    if (stopped()) break;
    report(spec.label());
    SweepPoint point;
    point.run = run_engine(scene, spec, run_options);
    if (point.run.interrupted) break;  // a half-run point says nothing; keep the others
    if (point.run.failure || (!use_expect && result.reference_run->failure)) {
      point.error = {HUGE_VAL, HUGE_VAL};  // nothing to measure (a crash or a hang)
    } else {
      point.error =
          use_expect ? expectation_error(scene, *point.run.expect)
                     : position_error(scene, point.run.final_positions,
                                      result.reference_run->final_positions, point.run.final_state);
    }
    result.points.push_back(std::move(point));
    ++done;
  }
  result.interrupted = stopped();
  mark_pareto(result.points);
  return result;
}

// How far a point's median may be from its true value: half the interquartile range of its step
// times, and at least 5% of the median (separate runs of one setting differ by up to 4% here, more
// than the spread within a run shows).
double timing_noise(const Timing& t) {
  return std::max(t.spread_ms, 0.05 * t.median_ms);
}

// A point whose run failed outright (unstable, escaped, tunnelled) is no setting to choose,
// however fast or close it ended.
bool eligible(const SweepPoint& p) {
  if (!p.run.verdict) return true;
  const VerdictClass v = p.run.verdict->worst;
  return v != VerdictClass::kUnstable && v != VerdictClass::kEscaped &&
         v != VerdictClass::kTunnelled && v < VerdictClass::kError;
}

void mark_pareto(std::vector<SweepPoint>& points) {
  // Two medians closer than their noise together are the same speed: noise must not decide.
  for (SweepPoint& p : points) {
    const Timing& t = p.run.timing;
    const double e = p.error.rms;
    if (!eligible(p)) {
      p.pareto = false;
      continue;
    }
    p.pareto = std::none_of(points.begin(), points.end(), [&](const SweepPoint& q) {
      if (!eligible(q)) return false;
      const Timing& u = q.run.timing;
      const double noise = timing_noise(t) + timing_noise(u);
      const bool faster = u.median_ms < t.median_ms - noise;
      const bool no_slower = u.median_ms <= t.median_ms + noise;
      return &q != &p && no_slower && q.error.rms <= e && (faster || q.error.rms < e);
    });
  }
}

std::string sweep_scene_label(const SweepResult& r) {
  return r.variant ? r.scene + " (" + r.variant->key + "=" + r.variant->text + ")" : r.scene;
}

void print_sweep_table(std::ostream& out, const SweepResult& r) {
  out << "scene " << sweep_scene_label(r) << ": " << r.bodies << " bodies, " << r.steps
      << " steps; error against "
      << (r.reference == "expect" ? "the scene's expectations" : r.reference_label)
      << (r.interrupted ? " (interrupted: the points measured so far)" : "") << "\n\n";
  std::vector<std::string> header = {"engine", "ms/step", "+- ms", "err max m", "err rms m"};
  for (const MetricDef& def : metric_table()) {
    if (def.outputs & kSweep) header.push_back(def.column);
  }
  header.insert(header.end(), {"stable", "verdict", "pareto"});
  TextTable t(header);
  for (const SweepPoint& p : r.points) {
    const auto stable = p.run.stable();
    if (p.run.failure) {  // crash or hang: nothing was measured
      std::vector<std::string> row(header.size(), "-");
      row.front() = p.run.spec.label();
      row[header.size() - 2] = to_string(p.run.verdict->worst);
      row.back() = "";
      t.add(row);
      continue;
    }
    std::vector<std::string> row = {p.run.spec.label(), fmt_ms(p.run.timing.median_ms),
                                    fmt_ms(p.run.timing.spread_ms), fmt_g(p.error.max),
                                    fmt_g(p.error.rms)};
    for (const MetricDef& def : metric_table()) {
      if (def.outputs & kSweep) row.push_back(metric_cell(def, def.value(p.run.metrics)));
    }
    row.insert(row.end(),
               {stable ? (*stable ? "yes" : "NO") : "-",
                p.run.verdict ? to_string(p.run.verdict->worst) : "-", p.pareto ? "*" : ""});
    t.add(row);
  }
  t.print(out);
}

nlohmann::ordered_json sweep_json(const std::vector<SweepResult>& results) {
  using nlohmann::ordered_json;
  ordered_json j;
  j["schema"] = "chainbench.sweep/1";
  j["scenes"] = ordered_json::array();
  for (const SweepResult& r : results) {
    ordered_json s;
    s["scene"] = {{"name", r.scene}, {"bodies", r.bodies}, {"steps", r.steps}};
    if (r.variant) {
      s["scene"]["vary"] = {
          {"key", r.variant->key}, {"text", r.variant->text}, {"value", r.variant->value}};
    }
    s["reference"] = r.reference;
    s["reference_label"] = r.reference == "expect" ? r.reference : r.reference_label;
    if (r.reference_run) s["reference_ms_per_step"] = r.reference_run->timing.median_ms;
    s["interrupted"] = r.interrupted;
    s["points"] = ordered_json::array();
    for (const SweepPoint& p : r.points) {
      const Metrics& m = p.run.metrics;
      ordered_json point;
      point["engine"] = p.run.engine;
      point["label"] = p.run.spec.label();
      // A crash or a hang measured nothing: no time, so that it never reads as the fastest.
      const bool failed = p.run.failure.has_value();
      point["ms_per_step"] = failed ? ordered_json(nullptr) : ordered_json(p.run.timing.median_ms);
      point["ms_spread"] = failed ? ordered_json(nullptr) : ordered_json(p.run.timing.spread_ms);
      point["final_position_error"] = {{"max", json_number(p.error.max)},
                                       {"rms", json_number(p.error.rms)}};
      for (const MetricDef& def : metric_table()) {
        if (!(def.outputs & kSweep)) continue;
        const std::optional<double> v = def.value(m);
        point[def.sweep_key] = !v                              ? ordered_json(nullptr)
                               : def.kind == MetricKind::kFlag ? ordered_json(*v != 0.0)
                                                               : json_number(*v);
      }
      const auto stable = p.run.stable();
      point["stable"] = stable ? ordered_json(*stable) : ordered_json(nullptr);
      point["pareto"] = p.pareto;
      if (p.run.verdict) point["verdict"] = to_string(p.run.verdict->worst);
      if (p.run.failure) point["failure"] = *p.run.failure;
      if (const auto hits = p.run.counter("budget_hits")) point["budget_hits"] = *hits;
      point["degraded_steps"] = p.run.degraded_steps;
      s["points"].push_back(std::move(point));
    }
    j["scenes"].push_back(std::move(s));
  }
  return j;
}

void write_sweep_csv(std::ostream& out, const std::vector<SweepResult>& results) {
  out << "scene,engine,reference,ms_median,err_max,err_rms";
  for (const MetricDef& def : metric_table()) {
    if (def.outputs & kSweep) out << ',' << def.name;
  }
  out << ",stable,pareto,vary,verdict\n";
  for (const SweepResult& r : results) {
    for (const SweepPoint& p : r.points) {
      const Metrics& m = p.run.metrics;
      const auto stable = p.run.stable();
      // A crash or a hang measured nothing: its figures are empty (never 0 ms, never inf), and
      // its verdict column says which it was.
      const bool failed = p.run.failure.has_value();
      const auto figure = [&](double v, int digits) {
        return failed || !std::isfinite(v) ? std::string() : fmt_g(v, digits);
      };
      out << csv_field(r.scene) << ',' << csv_quoted(p.run.engine) << ',' << csv_quoted(r.reference)
          << ',' << figure(p.run.timing.median_ms, 6) << ',' << figure(p.error.max, 9) << ','
          << figure(p.error.rms, 9);
      for (const MetricDef& def : metric_table()) {
        if (def.outputs & kSweep) out << ',' << metric_csv(def, def.value(m));
      }
      out << ',' << (stable ? (*stable ? "1" : "0") : "") << ',' << (p.pareto ? 1 : 0) << ','
          << (r.variant ? r.variant->key + "=" + r.variant->text : "") << ','
          << (p.run.verdict ? to_string(p.run.verdict->worst) : "") << '\n';
    }
  }
}

}  // namespace chainbench
