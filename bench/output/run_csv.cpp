// SPDX-License-Identifier: MIT
// The run CSV (docs/output-formats.md §3): one row per engine.
#include "output/report.h"

#include "judge/metric_table.h"
#include "output/trace_writer.h"
#include "support/text_table.h"

namespace chainbench {
namespace {

// Every counter name some run's engine declares, once, in the order the runs first declare them.
std::vector<std::string> counter_column_names(const RunReport& r) {
  std::vector<std::string> names;
  for_each_counter_def(r, [&](const CounterDef& c) {
    if (std::find(names.begin(), names.end(), c.name) == names.end()) names.push_back(c.name);
  });
  return names;
}

}  // namespace

void write_run_csv(std::ostream& out, const RunReport& r) {
  // The metric columns (metric_table()): the first ones after the errors, the later ones after
  // the run's own figures, where each first appeared.
  auto metric_columns = [&](std::uint32_t where) {
    for (const MetricDef& def : metric_table()) {
      if (def.outputs & where) out << ',' << def.name;
    }
  };
  out << "scene,engine,bodies,steps,dt,ms_median,ms_mean,ms_p95,ms_p99,ms_max,setup_ms,err_max,"
         "err_rms";
  metric_columns(kRunCsv);
  out << ",stable,hash,resolve_calls,max_depth,budget_hits,crush_events,expect_max_error,"
         "expect_max_speed_error,expect_pass,verdict,degraded_steps";
  metric_columns(kRunCsvLate);
  out << ",counters";
  // Then every counter any run's engine declares as a column of its own, counter_NAME, in the
  // order the runs first declare them: empty for a run whose engine has no such counter.
  const std::vector<std::string> counter_names = counter_column_names(r);
  for (const std::string& name : counter_names)
    out << ",counter_" << name;
  out << '\n';
  auto num = [](const std::optional<double>& v) { return v ? fmt_g(*v, 9) : std::string(); };
  auto flag = [](const std::optional<bool>& v) {
    return v ? std::string(*v ? "1" : "0") : std::string();
  };
  auto metric_cells = [&](const Metrics& m, std::uint32_t where) {
    for (const MetricDef& def : metric_table()) {
      if (def.outputs & where) out << ',' << metric_csv(def, def.value(m));
    }
  };
  auto row = [&](const EngineRun& run) {
    const Comparison* c = comparison_of(r, run);
    const Metrics& m = run.metrics;
    out << csv_field(r.scene->name) << ',' << csv_quoted(run.engine) << ','
        << r.scene->bodies.size() << ',' << r.scene->steps << ',' << fmt_g(r.scene->dt, 9) << ','
        << fmt_g(run.timing.median_ms, 6) << ',' << fmt_g(run.timing.mean_ms, 6) << ','
        << fmt_g(run.timing.p95_ms, 6) << ',' << fmt_g(run.timing.p99_ms, 6) << ','
        << fmt_g(run.timing.max_ms, 6) << ',' << fmt_g(run.timing.setup_ms, 6) << ','
        << (c ? fmt_g(c->error.max, 9) : "") << ',' << (c ? fmt_g(c->error.rms, 9) : "");
    metric_cells(m, kRunCsv);
    out << ',' << flag(run.stable()) << ',' << hex(run.hash) << ',';
    // The first CSV's four counter columns, filled by any engine with counters of those names.
    out << num(run.counter("resolve_calls")) << ',' << num(run.counter("max_depth")) << ','
        << num(run.counter("budget_hits")) << ',' << num(run.counter("crush_events"));
    out << ',' << (run.expect ? fmt_g(run.expect->max_error, 9) : "") << ','
        << (run.expect && run.expect->has_speed ? fmt_g(run.expect->max_speed_error, 9) : "") << ','
        << (run.expect ? (run.expect->pass ? "1" : "0") : "") << ','
        << (run.verdict ? to_string(run.verdict->worst) : "") << ',' << run.degraded_steps;
    metric_cells(m, kRunCsvLate);
    out << ',';
    const std::vector<CounterDef>& defs = run.counter_defs();
    std::string counters;
    for (std::size_t c = 0; c < defs.size() && c < run.counters.size(); ++c)
      counters += (c ? ";" : "") + defs[c].name + '=' + fmt_g(run.counters[c], 9);
    out << csv_quoted(counters);
    for (const std::string& name : counter_names)
      out << ',' << num(run.counter(name));
    out << '\n';
  };
  for (const EngineRun& run : r.runs)
    row(run);
  if (r.reference) row(*r.reference);
}

}  // namespace chainbench
