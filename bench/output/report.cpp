// SPDX-License-Identifier: MIT
#include "output/report.h"

#include "judge/metric_table.h"
#include "output/trace_writer.h"
#include "support/text_table.h"

#include <algorithm>
#include <cmath>

namespace chainbench {
namespace {

using nlohmann::ordered_json;

const EngineRun* reference_run(const RunReport& r) {
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
  auto note = [&](const EngineRun& run) {
    for (const CounterDef& c : run.counter_defs()) {
      const bool known = std::any_of(columns.begin(), columns.end(),
                                     [&](const auto& col) { return col.first == c.column; });
      if (!c.column.empty() && !known) columns.emplace_back(c.column, c.name);
    }
  };
  for (const EngineRun& run : r.runs)
    note(run);
  if (r.reference) note(*r.reference);
  return columns;
}

// Every counter name some run's engine declares, once, in the order the runs first declare them.
std::vector<std::string> counter_column_names(const RunReport& r) {
  std::vector<std::string> names;
  auto note = [&](const EngineRun& run) {
    for (const CounterDef& c : run.counter_defs()) {
      if (std::find(names.begin(), names.end(), c.name) == names.end()) names.push_back(c.name);
    }
  };
  for (const EngineRun& run : r.runs)
    note(run);
  if (r.reference) note(*r.reference);
  return names;
}

ordered_json optional_number(const std::optional<double>& v) {
  return v ? json_number(*v) : ordered_json(nullptr);
}

// Every entry's outcome: the expected value, the actual one at the worst state checked, the
// error there and whether the entry passed.
ordered_json expect_result_json(const Scene& s, const ExpectResult& r) {
  ordered_json j = {{"max_error", json_number(r.max_error)}, {"pass", r.pass}};
  if (r.has_speed) j["max_speed_error"] = json_number(r.max_speed_error);
  j["position_pass"] = r.position_pass;
  j["speed_pass"] = r.speed_pass;
  j["near_miss"] = r.near_miss;
  ordered_json entries = ordered_json::array();
  for (const ExpectOutcome& o : r.entries) {
    ordered_json e = expectation_json(s, s.expect[o.index]);
    if (o.body) e["worst_body"] = s.bodies[*o.body].name;
    if (o.other) e["other_body"] = s.bodies[*o.other].name;
    if (o.state >= 0) {
      e["step"] = o.state;
      const Expectation::Kind kind = s.expect[o.index].kind;
      if (kind == Expectation::Kind::kCenter || kind == Expectation::Kind::kMoved ||
          kind == Expectation::Kind::kBounds) {
        e["actual"] = {json_number(o.position.x), json_number(o.position.y)};
      } else {
        e["actual"] = json_number(o.value);
      }
    }
    e["error"] = json_number(o.error);
    e["unit"] = is_speed(s.expect[o.index].kind) ? "m/s" : "m";
    e["limit"] = json_number(o.limit);
    e["margin"] = json_number(o.margin);
    e["pass"] = o.pass;
    if (!o.pass) e["near_miss"] = o.near;
    if (o.beside) e["beside"] = true;  // on: not over the other along x
    entries.push_back(std::move(e));
  }
  j["entries"] = std::move(entries);
  return j;
}

}  // namespace

ordered_json json_number(double v) {
  return std::isfinite(v) ? ordered_json(v) : ordered_json(nullptr);
}

ordered_json expectation_json(const Scene& s, const Expectation& e) {
  ordered_json j;
  j["kind"] = to_string(e.kind);
  if (e.kind != Expectation::Kind::kNoOverlap)
    j["body"] = e.body == Expectation::kEveryDynamic ? std::string("*") : s.bodies[e.body].name;
  switch (e.kind) {
    case Expectation::Kind::kCenter:
      j["center"] = {e.center.x, e.center.y};
      j["tolerance"] = e.tolerance;
      break;
    case Expectation::Kind::kMoved:
      j["moved"] = {e.moved.x, e.moved.y};
      j["tolerance"] = e.tolerance;
      break;
    case Expectation::Kind::kBounds:
      j["min"] = {optional_number(e.min_x), optional_number(e.min_y)};
      j["max"] = {optional_number(e.max_x), optional_number(e.max_y)};
      break;
    case Expectation::Kind::kAtRest:
      j["at_rest"] = e.speed;
      break;
    case Expectation::Kind::kNoOverlap:
      j["no_overlap"] = e.depth;
      if (!e.bodies.empty()) {
        ordered_json names = ordered_json::array();
        for (const std::size_t b : e.bodies)
          names.push_back(s.bodies[b].name);
        j["bodies"] = std::move(names);
      }
      break;
    case Expectation::Kind::kAbove:
    case Expectation::Kind::kBelow:
    case Expectation::Kind::kOn:
      j[to_string(e.kind)] = s.bodies[e.other].name;
      j["tolerance"] = e.tolerance;
      break;
    case Expectation::Kind::kSqueezed:
      j["squeezed"] = true;
      j["tolerance"] = e.tolerance;
      break;
  }
  if (e.windowed()) {
    j["from_step"] = e.first_state(s.steps);
    j["to_step"] = e.last_state(s.steps);
  }
  return j;
}

void compare(RunReport& report) {
  report.comparison.clear();
  const EngineRun* ref = reference_run(report);
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

namespace {

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

// What the run JSON writes beside a metric's value (docs/output-formats.md §2.5).
void metric_details(ordered_json& m, const MetricDef& def, const Scene& s, const Metrics& mt) {
  const std::string_view name = def.name;
  if (name == "max_penetration") {
    if (mt.worst_overlap) {
      const PairOverlap& w = *mt.worst_overlap;
      m["worst_overlap"] = {{"bodies", {s.bodies[w.a].name, s.bodies[w.b].name}},
                            {"depth", json_number(w.depth)},
                            {"tolerance", json_number(w.tolerance)},
                            {"step", w.step}};
    } else {
      m["worst_overlap"] = nullptr;  // measured: nothing overlapped
    }
  } else if (name == "peak_speed") {
    m["peak_speed_body"] = s.bodies[mt.peak_speed_body].name;
    m["peak_speed_step"] = mt.peak_speed_step;
  } else if (name == "speed_bound") {
    if (!mt.speed_unbounded.empty()) m["speed_unbounded"] = mt.speed_unbounded;
  } else if (name == "in_bounds") {
    m["escaped"] = ordered_json::array();
    for (const std::size_t b : mt.escaped)
      m["escaped"].push_back(s.bodies[b].name);
  } else if (name == "tunnelled" && mt.tunnel) {
    m["tunnelling"] = {{"body", s.bodies[mt.tunnel->body].name},
                       {"through", s.bodies[mt.tunnel->through].name},
                       {"step", mt.tunnel->step},
                       {"count", mt.tunnel_count}};
  }
}

// The run's `metrics` block: every metric of the groups measured, as the table orders them.
ordered_json metrics_json(const Scene& s, const Metrics& mt) {
  ordered_json m = ordered_json::object();
  for (const MetricDef& def : metric_table()) {
    if (!measured(mt, def.group) || *def.json_key == '\0') continue;
    const std::optional<double> v = def.value(mt);
    const ordered_json value = !v                              ? ordered_json(nullptr)
                               : def.kind == MetricKind::kFlag ? ordered_json(*v != 0.0)
                                                               : json_number(*v);
    if (*def.json_block == '\0') {
      m[def.json_key] = value;
    } else {
      m[def.json_block][def.json_key] = value;
    }
    metric_details(m, def, s, mt);
  }
  return m;
}

ordered_json verdict_json(const Verdict& v) {
  ordered_json findings = ordered_json::array();
  for (const Finding& f : v.findings) {
    ordered_json finding = {{"class", to_string(f.what)}, {"detail", f.detail}};
    if (f.margin) finding["margin"] = json_number(*f.margin);
    if (f.tolerance) finding["tolerance"] = json_number(*f.tolerance);
    if (f.margin || f.near) finding["near_miss"] = f.near;
    findings.push_back(std::move(finding));
  }
  return {{"class", to_string(v.worst)},
          {"detail", v.findings.empty() ? "" : v.findings[0].detail},
          {"near_miss", v.near_miss()},
          {"findings", std::move(findings)}};
}

}  // namespace

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
  const EngineRun* ref = reference_run(r);
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

ordered_json run_json(const RunReport& r) {
  const Scene& s = *r.scene;
  ordered_json j;
  j["schema"] = "chainbench.run/1";
  j["scene"] = {{"name", s.name}, {"bodies", s.bodies.size()}, {"steps", s.steps}, {"dt", s.dt}};
  if (!s.description.empty()) j["scene"]["description"] = s.description;
  if (!s.family.empty()) j["scene"]["family"] = s.family;
  // Sizes and kinds in scene order, so that tools can draw the final states.
  ordered_json half = ordered_json::array(), kinds = ordered_json::array();
  ordered_json names = ordered_json::array(), centers = ordered_json::array();
  for (const SceneBody& b : s.bodies) {
    half.push_back({b.half_extents.x, b.half_extents.y});
    kinds.push_back(to_string(b.kind));
    names.push_back(b.name);
    centers.push_back({b.center.x, b.center.y});
  }
  j["scene"]["half_extents"] = std::move(half);
  j["scene"]["kinds"] = std::move(kinds);
  j["scene"]["names"] = std::move(names);
  j["scene"]["centers"] = std::move(centers);  // as built
  if (s.has_lifetimes()) {  // the states each body is in: from_step..to_step (null: the last)
    ordered_json from = ordered_json::array(), to = ordered_json::array();
    for (const SceneBody& b : s.bodies) {
      from.push_back(b.from_step);
      to.push_back(b.to_step < s.steps ? ordered_json(b.to_step) : ordered_json(nullptr));
    }
    j["scene"]["from_step"] = std::move(from);
    j["scene"]["to_step"] = std::move(to);
  }
  if (!s.expect.empty()) {
    j["scene"]["expect"] = ordered_json::array();
    for (const Expectation& e : s.expect)
      j["scene"]["expect"].push_back(expectation_json(s, e));
  }
  if (s.penetration_tolerance) j["scene"]["penetration_tolerance"] = *s.penetration_tolerance;
  if (r.reference_spec) j["reference"] = r.reference_spec->str();
  j["interrupted"] = r.interrupted;
  const std::vector<LimitNote> limit_notes = exceeded_limits(r);
  auto run_entry = [&](const EngineRun& run) {
    ordered_json e;
    e["engine"] = run.engine;
    e["label"] = run.spec.label();
    e["gate"] = is_gate(run.spec);  // the setting under test (registry.h)
    if (const std::string& caveat = engine_def(run.spec.engine).caveat; !caveat.empty())
      e["caveat"] = caveat;
    if (run.failure) {  // its child process crashed or hung: nothing was measured
      e["failure"] = *run.failure;
      e["verdict"] = verdict_json(*run.verdict);
      return e;
    }
    // A body out of the world at the end has no position: null.
    ordered_json positions = ordered_json::array();
    for (std::size_t i = 0; i < run.final_positions.size(); ++i) {
      const Vec2d p = run.final_positions[i];
      positions.push_back(run.present_at_end(s, i)
                              ? ordered_json{json_number(p.x), json_number(p.y)}
                              : ordered_json(nullptr));
    }
    e["final_positions"] = std::move(positions);
    if (s.rotation) {
      ordered_json angles = ordered_json::array();
      for (std::size_t i = 0; i < run.final_angles.size(); ++i)
        angles.push_back(run.present_at_end(s, i) ? json_number(run.final_angles[i])
                                                  : ordered_json(nullptr));
      e["final_angles"] = std::move(angles);
    }
    e["ms_per_step"] = {{"median", run.timing.median_ms}, {"mean", run.timing.mean_ms},
                        {"p95", run.timing.p95_ms},       {"p99", run.timing.p99_ms},
                        {"max", run.timing.max_ms},       {"spread", run.timing.spread_ms},
                        {"samples", run.timing.samples}};
    e["setup_ms"] = run.timing.setup_ms;
    if (!run.stages.empty()) {
      ordered_json stages = ordered_json::object();
      for (const StageMean& st : run.stages)
        stages[st.name] = json_number(st.ms);
      e["stages_ms"] = std::move(stages);
    }
    ordered_json m = metrics_json(s, run.metrics);
    if (const auto stable = run.stable()) m["stable"] = *stable;
    m["hash"] = hex(run.hash);
    e["metrics"] = std::move(m);
    ordered_json counters = ordered_json::object();
    const std::vector<CounterDef>& defs = run.counter_defs();
    for (std::size_t c = 0; c < defs.size() && c < run.counters.size(); ++c)
      counters[defs[c].name] = json_number(run.counters[c]);
    // An engine may also keep its counters under the key its first JSON had (chain_stats).
    const std::string& block = engine_def(run.spec.engine).stats_block;
    if (!block.empty()) e[block] = counters;
    e["counters"] = std::move(counters);
    e["degraded_steps"] = run.degraded_steps;
    ordered_json exceeded = ordered_json::array();
    for (const LimitNote& n : limit_notes) {
      if (n.engine != run.spec.label()) continue;
      exceeded.push_back({{"what", n.what},
                          {"value", json_number(n.value)},
                          {"unit", n.unit},
                          {"speed_limit", json_number(n.speed_limit)},
                          {"asked", json_number(n.asked)},
                          {"source", n.source}});
    }
    if (!exceeded.empty()) e["limits_exceeded"] = std::move(exceeded);
    if (run.expect) e["expect"] = expect_result_json(s, *run.expect);
    if (run.verdict) e["verdict"] = verdict_json(*run.verdict);
    return e;
  };
  j["runs"] = ordered_json::array();
  for (const EngineRun& run : r.runs)
    j["runs"].push_back(run_entry(run));
  if (r.reference) j["reference_run"] = run_entry(*r.reference);
  j["comparison"] = ordered_json::array();
  for (const Comparison& c : r.comparison) {
    j["comparison"].push_back(
        {{"engine", c.engine},
         {"reference", c.reference},
         {"final_position_error",
          {{"max", json_number(c.error.max)}, {"rms", json_number(c.error.rms)}}},
         {"speedup", json_number(c.speedup)}});
  }
  return j;
}

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
