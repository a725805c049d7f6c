#include "report.h"

#include "text_table.h"

#include <cmath>

namespace chainbench {
namespace {

using nlohmann::ordered_json;

const EngineRun* reference_run(const RunReport& r) {
  if (r.reference_spec.empty()) return nullptr;
  if (r.reference) return &*r.reference;
  for (const EngineRun& run : r.runs) {
    if (run.engine == r.reference_spec) return &run;
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

// The canonical spec is long for a table: show the keys that differ from the defaults.
std::string short_name(const std::string& spec) {
  return parse_engine_spec(spec).short_str();
}

}  // namespace

ordered_json json_number(double v) {
  return std::isfinite(v) ? ordered_json(v) : ordered_json(nullptr);
}

void compare(RunReport& report) {
  report.comparison.clear();
  const EngineRun* ref = reference_run(report);
  if (!ref) return;
  for (const EngineRun& run : report.runs) {
    if (&run == ref) continue;
    Comparison c;
    c.engine = run.engine;
    c.reference = ref->engine;
    c.error = position_error(*report.scene, run.final_positions, ref->final_positions);
    c.speedup = run.timing.median_ms > 0.0 ? ref->timing.median_ms / run.timing.median_ms : 0.0;
    report.comparison.push_back(c);
  }
}

void print_run_table(std::ostream& out, const RunReport& r) {
  const Scene& s = *r.scene;
  out << "scene " << s.name << ": " << s.bodies.size() << " bodies, " << s.steps << " steps of "
      << fmt_g(s.dt, 4) << " s";
  if (!r.reference_spec.empty()) out << "; reference " << short_name(r.reference_spec);
  out << "\n\n";
  const bool expect = !s.expect.empty();
  std::vector<std::string> header = {"engine",    "ms/step",         "x ref",     "err max m",
                                     "err rms m", "EFD/body-step m", "max pen m", "stable"};
  if (expect) header.push_back("expect");
  TextTable t(header);
  auto add = [&](const EngineRun& run, bool is_reference) {
    const Comparison* c = comparison_of(r, run);
    std::vector<std::string> row = {short_name(run.engine) + (is_reference ? " (ref)" : ""),
                                    fmt_ms(run.timing.median_ms),
                                    c ? fmt_g(c->speedup, 3) : (is_reference ? "1" : "-"),
                                    c ? fmt_g(c->error.max) : (is_reference ? "0" : "-"),
                                    c ? fmt_g(c->error.rms) : (is_reference ? "0" : "-"),
                                    opt(run.metrics.efd_per_body_step),
                                    opt(run.metrics.max_penetration),
                                    yes_no(run.stable())};
    if (expect)
      row.push_back(
          run.expect ? (run.expect->pass ? "pass " : "FAIL ") + fmt_g(run.expect->max_error) : "-");
    t.add(row);
  };
  const EngineRun* ref = reference_run(r);
  for (const EngineRun& run : r.runs)
    add(run, &run == ref);
  if (r.reference) add(*r.reference, true);
  t.print(out);
}

ordered_json run_json(const RunReport& r) {
  const Scene& s = *r.scene;
  ordered_json j;
  j["schema"] = "chainbench.run/1";
  j["scene"] = {{"name", s.name}, {"bodies", s.bodies.size()}, {"steps", s.steps}, {"dt", s.dt}};
  if (!s.description.empty()) j["scene"]["description"] = s.description;
  // Sizes and kinds in scene order, so that tools can draw the final states.
  ordered_json half = ordered_json::array(), kinds = ordered_json::array();
  for (const SceneBody& b : s.bodies) {
    half.push_back({b.half_extents.x, b.half_extents.y});
    kinds.push_back(to_string(b.kind));
  }
  j["scene"]["half_extents"] = std::move(half);
  j["scene"]["kinds"] = std::move(kinds);
  if (!r.reference_spec.empty()) j["reference"] = r.reference_spec;
  auto run_entry = [&](const EngineRun& run) {
    ordered_json e;
    e["engine"] = run.engine;
    e["label"] = short_name(run.engine);
    ordered_json positions = ordered_json::array();
    for (const Vec2d& p : run.final_positions)
      positions.push_back({json_number(p.x), json_number(p.y)});
    e["final_positions"] = std::move(positions);
    if (s.rotation) {
      ordered_json angles = ordered_json::array();
      for (const double a : run.final_angles)
        angles.push_back(json_number(a));
      e["final_angles"] = std::move(angles);
    }
    e["ms_per_step"] = {{"median", run.timing.median_ms},
                        {"mean", run.timing.mean_ms},
                        {"p95", run.timing.p95_ms},
                        {"samples", run.timing.samples}};
    e["setup_ms"] = run.timing.setup_ms;
    ordered_json m;
    const Metrics& mt = run.metrics;
    if (mt.efd_total) {
      m["energy_free_displacement"] = {{"total", json_number(*mt.efd_total)},
                                       {"per_body_step", json_number(*mt.efd_per_body_step)},
                                       {"max_step", json_number(*mt.efd_max_step)}};
    }
    if (mt.max_penetration) m["max_penetration"] = json_number(*mt.max_penetration);
    if (mt.peak_speed) {
      m["peak_speed"] = json_number(*mt.peak_speed);
      m["speed_bound"] = json_number(*mt.speed_bound);
      m["finite"] = *mt.finite;
      m["in_bounds"] = *mt.in_bounds;
      m["blow_up"] = *mt.blow_up;
    }
    if (const auto stable = run.stable()) m["stable"] = *stable;
    m["hash"] = hex(run.hash);
    e["metrics"] = std::move(m);
    if (run.chain) {
      e["chain_stats"] = {{"resolve_calls", run.chain->resolve_calls_per_step},
                          {"max_depth", run.chain->max_depth},
                          {"budget_hits", run.chain->budget_hits},
                          {"crush_events", run.chain->crush_events},
                          {"passes", run.chain->passes_per_step},
                          {"contacts", run.chain->contacts_per_step}};
    }
    if (run.expect)
      e["expect"] = {{"max_error", json_number(run.expect->max_error)}, {"pass", run.expect->pass}};
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
  out << "scene,engine,bodies,steps,dt,ms_median,ms_mean,ms_p95,setup_ms,err_max,err_rms,efd_total,"
         "efd_per_body_step,efd_max_step,max_penetration,peak_speed,finite,in_bounds,stable,hash,"
         "resolve_calls,max_depth,budget_hits,crush_events,expect_max_error,expect_pass\n";
  auto num = [](const std::optional<double>& v) { return v ? fmt_g(*v, 9) : std::string(); };
  auto flag = [](const std::optional<bool>& v) {
    return v ? std::string(*v ? "1" : "0") : std::string();
  };
  auto row = [&](const EngineRun& run) {
    const Comparison* c = comparison_of(r, run);
    const Metrics& m = run.metrics;
    out << r.scene->name << ",\"" << run.engine << "\"," << r.scene->bodies.size() << ','
        << r.scene->steps << ',' << fmt_g(r.scene->dt, 9) << ',' << fmt_g(run.timing.median_ms, 6)
        << ',' << fmt_g(run.timing.mean_ms, 6) << ',' << fmt_g(run.timing.p95_ms, 6) << ','
        << fmt_g(run.timing.setup_ms, 6) << ',' << (c ? fmt_g(c->error.max, 9) : "") << ','
        << (c ? fmt_g(c->error.rms, 9) : "") << ',' << num(m.efd_total) << ','
        << num(m.efd_per_body_step) << ',' << num(m.efd_max_step) << ',' << num(m.max_penetration)
        << ',' << num(m.peak_speed) << ',' << flag(m.finite) << ',' << flag(m.in_bounds) << ','
        << flag(run.stable()) << ',' << hex(run.hash) << ',';
    if (run.chain) {
      out << fmt_g(run.chain->resolve_calls_per_step, 9) << ',' << run.chain->max_depth << ','
          << run.chain->budget_hits << ',' << run.chain->crush_events;
    } else {
      out << ",,,";
    }
    out << ',' << (run.expect ? fmt_g(run.expect->max_error, 9) : "") << ','
        << (run.expect ? (run.expect->pass ? "1" : "0") : "") << '\n';
  };
  for (const EngineRun& run : r.runs)
    row(run);
  if (r.reference) row(*r.reference);
}

}  // namespace chainbench
