// SPDX-License-Identifier: MIT
// The run table for people, and what both it and the files need: the comparison with the
// reference and the engine limits a scene exceeds. The JSON is run_json.cpp's, the CSV
// run_csv.cpp's.
#include "output/report.h"

#include "judge/metric_table.h"
#include "support/text_table.h"

#include <algorithm>
#include <cmath>

namespace chainbench {
namespace {

std::string opt(const std::optional<double>& v) {
  return v ? fmt_g(*v) : "-";
}

std::string yes_no(const std::optional<bool>& v) {
  return v ? (*v ? "yes" : "NO") : "-";
}

// The counter columns of the table: each column title some run's engine declares, once, in the
// order the runs first show them.
std::vector<std::pair<std::string, std::string>> counter_columns(const RunReport& r) {
  std::vector<std::pair<std::string, std::string>> columns;  // (title, counter name)
  for_each_counter_def(r, [&](const CounterDef& c) {
    const bool known = std::any_of(columns.begin(), columns.end(),
                                   [&](const auto& col) { return col.first == c.column; });
    if (!c.column.empty() && !known) columns.emplace_back(c.column, c.name);
  });
  return columns;
}

// The expectation cells: the largest error of the entries judged in metres, and of those judged
// in m/s (a rest limit's excess speed), each with its own pass or FAIL so that neither hides the
// other; "near" when every failure of that kind is within a tenth of its tolerance.
std::string expect_cell(const EngineRun& run, const Scene& scene, bool speed) {
  if (!run.expect) return "-";
  const ExpectResult& e = *run.expect;
  const bool pass = speed ? e.speed_pass : e.position_pass;
  bool near = true;
  for (const ExpectOutcome& o : e.entries) {
    if (!o.pass && is_speed(scene.expect[o.index].kind) == speed) near = near && o.near;
  }
  const std::string verdict = pass ? "pass " : (near ? "FAIL (near) " : "FAIL ");
  return verdict + fmt_g(speed ? e.max_speed_error : e.max_error);
}

// The engines that meet every expectation, and those that miss some, by label.
void print_expectation_summary(std::ostream& out, const RunReport& r, const EngineRun* ref) {
  const Scene& s = *r.scene;
  // Near misses (every failed entry within a tenth of its tolerance) apart from clear ones.
  std::string met, missed, near;
  auto note = [&](const EngineRun& run) {
    if (!run.expect) return;
    std::string& list = run.expect->pass ? met : (run.expect->near_miss ? near : missed);
    list += (list.empty() ? "" : ", ") + run.spec.label() + (&run == ref ? " (ref)" : "");
  };
  for (const EngineRun& run : r.runs)
    note(run);
  if (r.reference) note(*r.reference);
  out << "\nexpectations (" << s.expect.size() << (s.expect.size() == 1 ? " entry" : " entries")
      << "): met by " << (met.empty() ? "no engine" : met);
  if (!missed.empty()) out << "; missed by " << missed;
  if (!near.empty()) out << "; missed narrowly (within a tenth of the tolerance) by " << near;
  out << "\n";
  if (ref && ref->expect && !ref->expect->pass) {
    out << "note: the reference " << ref->spec.label()
        << " misses the expectations: the vs-ref columns measure distance from it, not error\n";
  }
}

// The fastest the scene asks any body to move: its stated speeds (initial, kinematic, driven),
// and what any run measured (peak m/s), with where that figure comes from.
struct Asked {
  double speed = 0.0;
  std::string source;
};

Asked asked_speed(const RunReport& r) {
  const Scene& s = *r.scene;
  Asked a;
  for (const SceneBody& b : s.bodies) {
    const double v = std::hypot(b.velocity.x, b.velocity.y);
    if (v > a.speed) a = {v, b.name + "'s initial velocity"};
  }
  for (const Driver& d : s.drivers) {
    const double v = std::hypot(d.velocity.x, d.velocity.y);
    if (v > a.speed) a = {v, "the drive of " + s.bodies[d.body].name};
  }
  // A measured speed counts when it is beyond the stated ones by more than a float engine's
  // rounding (0.1%): the scene's own words say it best. Only a stable run's: a body that passed
  // through what should have stopped it (or blew up) shows no speed the scene asks.
  auto measured = [&](const EngineRun& run) {
    const Metrics& m = run.metrics;
    if (run.stable() != true) return;
    if (m.peak_speed && *m.peak_speed > a.speed * 1.001)
      a = {*m.peak_speed, s.bodies[m.peak_speed_body].name + " in " + run.spec.label() + "'s run"};
  };
  for (const EngineRun& run : r.runs)
    measured(run);
  if (r.reference) measured(*r.reference);
  return a;
}

}  // namespace

const EngineRun* reference_of(const RunReport& r) {
  if (!r.reference_spec) return nullptr;
  if (r.reference) return &*r.reference;
  for (const EngineRun& run : r.runs) {
    if (run.spec == *r.reference_spec) return &run;
  }
  return nullptr;
}

const Comparison* comparison_of(const RunReport& r, const EngineRun& run) {
  for (const Comparison& c : r.comparison) {
    if (c.engine == run.engine) return &c;
  }
  return nullptr;
}

void compare(RunReport& report) {
  report.comparison.clear();
  const EngineRun* ref = reference_of(report);
  if (!ref || ref->failure) return;
  for (const EngineRun& run : report.runs) {
    if (&run == ref || run.failure) continue;  // a run that failed has no positions
    Comparison c;
    c.engine = run.engine;
    c.reference = ref->engine;
    c.error =
        position_error(*report.scene, run.final_positions, ref->final_positions, run.final_state);
    c.speedup = run.timing.median_ms > 0.0 ? ref->timing.median_ms / run.timing.median_ms : 0.0;
    report.comparison.push_back(c);
  }
}

std::vector<LimitNote> exceeded_limits(const RunReport& r) {
  std::vector<LimitNote> notes;
  const Asked asked = asked_speed(r);
  auto check = [&](const EngineRun& run) {
    for (const EngineLimit& l : engine_def(run.spec.engine).limits) {
      if (!l.speed) continue;
      const double limit = l.speed(run.spec, *r.scene);
      if (asked.speed > limit)
        notes.push_back(
            {run.spec.label(), l.what, l.value, l.unit, limit, asked.speed, asked.source});
    }
  };
  for (const EngineRun& run : r.runs)
    check(run);
  if (r.reference) check(*r.reference);
  return notes;
}

void print_run_table(std::ostream& out, const RunReport& r) {
  const Scene& s = *r.scene;
  out << "scene " << s.name << ": " << s.bodies.size() << " bodies, " << s.steps << " steps of "
      << fmt_g(s.dt, 4) << " s";
  if (r.reference_spec) out << "; reference " << r.reference_spec->label();
  if (r.interrupted) out << " (interrupted: the engines that finished)";
  out << "\n\n";
  const bool expect = !s.expect.empty();
  bool expect_m = false, expect_speed = false;
  for (const Expectation& e : s.expect)
    (is_speed(e.kind) ? expect_speed : expect_m) = true;
  const auto columns = counter_columns(r);
  std::vector<std::string> header = {"engine", "ms/step", "max ms", "x ref"};
  if (expect_m) header.push_back("expect m");
  if (expect_speed) header.push_back("rest m/s");
  header.insert(header.end(), {"vs ref max m", "vs ref rms m"});
  for (const MetricDef& def : metric_table()) {
    if (def.outputs & kRunTable) header.push_back(def.column);
  }
  for (const auto& column : columns)
    header.push_back(column.first);
  header.insert(header.end(), {"stable", "verdict"});
  TextTable t(header);
  auto add = [&](const EngineRun& run, bool is_reference) {
    const Comparison* c = comparison_of(r, run);
    if (run.failure) {  // crash, hang or error: nothing was measured
      std::vector<std::string> row(header.size(), "-");
      row.front() = run.spec.label() + (is_reference ? " (ref)" : "");
      row.back() = to_string(run.verdict->worst);
      t.add(row);
      return;
    }
    std::vector<std::string> row = {run.spec.label() + (is_reference ? " (ref)" : ""),
                                    fmt_ms(run.timing.median_ms), fmt_ms(run.timing.max_ms),
                                    c ? fmt_g(c->speedup, 3) : (is_reference ? "1" : "-")};
    if (expect_m) row.push_back(expect_cell(run, s, false));
    if (expect_speed) row.push_back(expect_cell(run, s, true));
    row.insert(row.end(), {c ? fmt_g(c->error.max) : (is_reference ? "0" : "-"),
                           c ? fmt_g(c->error.rms) : (is_reference ? "0" : "-")});
    for (const MetricDef& def : metric_table()) {
      if (def.outputs & kRunTable) row.push_back(metric_cell(def, def.value(run.metrics)));
    }
    for (const auto& column : columns)
      row.push_back(opt(run.counter(column.second)));
    row.push_back(yes_no(run.stable()));
    row.push_back(run.verdict ? to_string(run.verdict->worst) : "-");
    t.add(row);
  };
  const EngineRun* ref = reference_of(r);
  for (const EngineRun& run : r.runs)
    add(run, &run == ref);
  if (r.reference) add(*r.reference, true);
  t.print(out);
  if (expect) print_expectation_summary(out, r, ref);
  // A scene faster than an engine lets anything move: its row cannot move bodies as the scene
  // asks (it may still meet an answer that does not hang on that speed), and say why.
  for (const LimitNote& n : exceeded_limits(r)) {
    out << "note: " << n.engine << " " << n.what << ", " << fmt_g(n.value, 9) << " " << n.unit
        << " (" << fmt_g(n.speed_limit, 4) << " m/s here); the scene asks " << fmt_g(n.asked, 4)
        << " m/s (" << n.source << "), so " << n.engine
        << " cannot move bodies as fast as the scene asks\n";
  }
  // What each verdict other than ok rests on.
  bool first = true;
  auto explain = [&](const EngineRun& run) {
    if (!run.verdict || run.verdict->ok()) return;
    if (first) out << "\n";
    first = false;
    out << run.spec.label() << ": " << run.verdict->str();
    if (run.verdict->findings.size() > 1)
      out << " (+" << run.verdict->findings.size() - 1 << " more in the JSON)";
    out << "\n";
  };
  for (const EngineRun& run : r.runs)
    explain(run);
  if (r.reference) explain(*r.reference);
}

}  // namespace chainbench
