// SPDX-License-Identifier: MIT
// chainbench.run/1 (docs/output-formats.md §2): the scene, every engine's run and the comparison.
#include "output/report.h"

#include "judge/metric_table.h"

#include <cmath>

namespace chainbench {
namespace {

using nlohmann::ordered_json;

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
    if (def.details) def.details(m, mt, s);
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

}  // namespace chainbench
