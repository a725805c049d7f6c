// SPDX-License-Identifier: MIT
#include "campaign/stress.h"

#include "judge/metric_table.h"
#include "output/report.h"
#include "run/runner.h"
#include "scenes/scene_library.h"
#include "support/child_process.h"
#include "support/text_table.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <map>

namespace chainbench {
namespace {

// What a child reports back through its pipe: plain data of a fixed size.
constexpr std::size_t kMaxCounters = 16;
struct Summary {
  double ms_per_step;
  double metrics[kMaxMetrics];  // metric_table()'s, in its order
  std::uint8_t measured[kMaxMetrics];
  double counters[kMaxCounters];
  char counter_names[kMaxCounters][32];
  char counter_columns[kMaxCounters][16];
  std::uint64_t degraded_steps;
  std::uint32_t counter_count;
  std::uint8_t expect_pass, judged, near_miss;
  char detail[480];
  char error[240];
};

Summary summarize_case(const StressCase& c, const EngineSpec& engine) {
  Summary s{};
  try {
    const Scene scene = make_scene(c.scene, c.sets);
    RunOptions options;
    options.step_mark = child_mark();  // for a crash to say where
    const EngineRun run = run_engine(scene, engine, options);
    const Metrics& m = run.metrics;
    const std::span<const MetricDef> table = metric_table();
    for (std::size_t k = 0; k < table.size(); ++k) {
      const std::optional<double> v = table[k].value(m);
      s.metrics[k] = v.value_or(0.0);
      s.measured[k] = v.has_value();
    }
    s.ms_per_step = run.timing.median_ms;
    s.expect_pass = !run.expect || run.expect->pass;
    s.degraded_steps = run.degraded_steps;
    s.counter_count = static_cast<std::uint32_t>(std::min(run.counters.size(), kMaxCounters));
    for (std::size_t k = 0; k < s.counter_count; ++k) {
      s.counters[k] = run.counters[k];
      std::snprintf(s.counter_names[k], sizeof s.counter_names[k], "%s", run.defs[k].name.c_str());
      std::snprintf(s.counter_columns[k], sizeof s.counter_columns[k], "%s",
                    run.defs[k].column.c_str());
    }
    s.judged = static_cast<std::uint8_t>(run.verdict->worst);
    s.near_miss = run.verdict->near_miss();
    if (!run.verdict->findings.empty())
      std::snprintf(s.detail, sizeof s.detail, "%s", run.verdict->findings.front().detail.c_str());
  } catch (const std::exception& e) {
    std::snprintf(s.error, sizeof s.error, "%s", e.what());
  }
  return s;
}

}  // namespace

std::string StressCase::label() const {
  std::string s = scene;
  for (const std::string& kv : sets)
    s += " " + kv;
  return s;
}

std::vector<StressCase> stress_cases() {
  std::vector<StressCase> cases;
  auto add = [&](const char* group, const char* scene, std::vector<std::string> sets, bool quick) {
    cases.push_back({group, scene, std::move(sets), quick});
  };
  for (const char* ratio : {"1", "100", "1e4", "1e6"}) {
    add("mass ratio, 3-box stack", "mass_ratio_stack", {"n=3", std::string("ratio=") + ratio},
        std::string(ratio) == "1e6");
  }
  for (const char* mass : {"100", "1e4", "1e6"}) {
    add("mass ratio, push chain", "push_into_wall", {"n=10", std::string("pusher_mass=") + mass},
        std::string(mass) == "1e6");
  }
  for (const char* n : {"10", "50", "100", "200"}) {
    add("tall stack", "stack",
        {std::string("n=") + n, std::string("steps=") + (std::string(n) == "50" ? "300" : "600")},
        std::string(n) == "50");
  }
  for (const char* n : {"10", "100", "1000", "10000"}) {
    add("long push chain into a wall", "push_into_wall", {std::string("n=") + n, "steps=120"},
        false);
  }
  add("long push chain into a wall", "push_into_wall", {"n=1000", "steps=60"}, true);
  add("tiny boxes", "stack", {"n=10", "size=0.01"}, true);
  add("huge boxes", "stack", {"n=10", "size=100"}, true);
  for (const char* offset : {"1e3", "1e5", "1e6"}) {
    add("far from the origin", "stack", {"n=10", std::string("offset=") + offset},
        std::string(offset) == "1e6");
  }
  add("far from the origin", "push_row", {"n=10", "offset=1e6"}, false);
  add("time step", "stack", {"n=10", "dt=0.1", "steps=30"}, true);
  add("time step", "stack", {"n=10", "dt=0.001", "steps=2000"}, false);
  add("time step", "stack", {"n=10", "dt=0.001", "steps=600"}, true);
  add("time step", "push_row", {"n=10", "dt=0.1", "steps=12"}, false);
  add("time step", "push_row", {"n=10", "dt=0.001", "steps=1200"}, false);
  // Large steps, up to the 1 s a scene allows, on what a game does every frame: a resting stack,
  // a driven push and the same push against friction, each over 3 s (180 steps at 1/60 s). Two
  // go into --quick.
  struct Step {
    const char* dt;  // empty: the scene's 1/60 s
    const char* steps;
  };
  for (const Step& t :
       {Step{"", "180"}, Step{"0.1", "30"}, Step{"0.35", "9"}, Step{"0.5", "6"}, Step{"1", "3"}}) {
    auto with_dt = [&](std::vector<std::string> sets) {
      if (*t.dt) sets.push_back(std::string("dt=") + t.dt);
      sets.push_back(std::string("steps=") + t.steps);
      return sets;
    };
    const bool half = std::string(t.dt) == "0.5";
    add("large time step", "stack", with_dt({"n=2"}), half);
    add("large time step", "push_stack", with_dt({"height=1"}), false);
    add("large time step", "push_stack", with_dt({"height=1", "friction=0.5"}), half);
  }
  for (const char* speed : {"10", "50", "100", "500"}) {
    add("fast body", "projectile", {std::string("speed=") + speed}, std::string(speed) == "100");
  }
  for (const char* overlap : {"0.25", "0.5", "0.75", "0.95"}) {
    add("deep overlap", "overlap_recovery", {std::string("overlap=") + overlap},
        std::string(overlap) == "0.95");
  }
  add("deep overlap", "overlapping_pile", {"n=1000"}, false);
  add("deep overlap", "overlapping_pile", {"n=200"}, true);
  add("squeeze", "static_squeeze", {}, true);
  add("squeeze", "lift_squeeze", {}, true);
  add("squeeze", "converging_walls", {"n=10"}, true);
  add("squeeze", "converging_walls", {"n=1000"}, false);
  // What a platformer's level asks: seams between tiles, fast crates, walking off a ledge,
  // friction on platforms and floors, gaps.
  add("level", "seam_slide", {"direction=-1"}, true);
  add("level", "seam_slide", {"direction=1"}, false);
  add("level", "seam_slide", {"direction=-1", "phase=0.001"}, false);
  add("level", "seam_landing", {"x=0.2"}, false);
  add("level", "seam_landing", {"x=0", "speed=20"}, true);
  add("level", "fast_drop", {"speed=25"}, false);
  add("level", "fast_drop", {"speed=200"}, false);
  add("level", "ledge_walk", {}, true);
  add("level", "platform_ride", {}, true);
  add("level", "rough_slide", {}, false);
  // Gaps between level grounds: no wider than the box (the one-tile gap), it crosses; wider by
  // more than two steps' travel, it falls in.
  add("level", "gap_cross", {}, true);
  add("level", "gap_cross", {"gap=0.9", "speed=8", "driven=0"}, false);
  add("level", "gap_cross", {"gap=0.95", "speed=8"}, false);
  add("level", "gap_cross", {"edge=0.25", "gap=0.25", "speed=30"}, false);
  add("level", "gap_cross", {"gap=1.5", "speed=8", "driven=0"}, false);
  // Conveyors: a crate set down on a running belt slips, then rides.
  add("level", "conveyor", {}, true);
  add("level", "conveyor", {"speed=-5", "mu=0.5", "steps=120"}, false);
  // Collision filtering: a character walks through crates it does not collide with.
  add("level", "filter_walk", {}, true);
  add("level", "filter_walk", {"speed=20"}, false);
  return cases;
}

VerdictClass StressVerdict::verdict() const {
  if (!skipped.empty()) return VerdictClass::kSkipped;
  if (hang) return VerdictClass::kHang;
  if (!finished) return VerdictClass::kCrash;
  if (!error.empty()) return VerdictClass::kError;
  return judged;
}

std::string StressVerdict::verdict_detail() const {
  if (!skipped.empty()) return skipped;
  const std::string at = (step > 0 ? " at step " + std::to_string(step) : std::string()) +
                         (out_of_memory ? ", out of memory" : "");
  if (hang) return "ran out of time" + at;
  if (!finished && signal != 0) return "died of signal " + std::to_string(signal) + at;
  if (!finished) return "exited with status " + std::to_string(exit_status) + " and no result" + at;
  if (!error.empty()) return error;
  return detail;
}

std::optional<double> StressVerdict::metric_named(std::string_view name) const {
  const std::span<const MetricDef> table = metric_table();
  for (std::size_t k = 0; k < table.size(); ++k) {
    if (name == table[k].name) return metric(k);
  }
  return std::nullopt;
}

bool StressVerdict::stable() const {
  // A flag not measured (a verdict made by hand) stands as the right value.
  auto is = [&](const char* flag, bool right) {
    return metric_named(flag).value_or(right ? 1.0 : 0.0) != 0.0;
  };
  return finished && error.empty() && is("finite", true) && is("in_bounds", true) &&
         !is("blow_up", false) && !is("tunnelled", false) && degraded_steps == 0;
}

bool StressVerdict::fatal() const {
  const VerdictClass v = verdict();
  return is_gate(engine) && v != VerdictClass::kOk && v != VerdictClass::kBudget &&
         known_failure.empty();
}

StressVerdict run_stress_case(const StressCase& c, const EngineSpec& engine, double timeout_s,
                              const std::atomic<bool>* stop) {
  StressVerdict v;
  v.case_label = c.label();
  v.group = c.group;
  v.engine = engine;
  try {
    if (std::string why = missing_capability(engine, make_scene(c.scene, c.sets)); !why.empty()) {
      v.skipped = why;
      return v;
    }
  } catch (const std::exception&) {
    // A case that cannot be built: the child says why, as an error verdict.
  }
  Summary s{};
  const ChildOutcome child =
      run_in_child([&] { return summarize_case(c, engine); }, s, timeout_s, stop);
  v.finished = child.finished, v.hang = child.hang, v.interrupted = child.interrupted;
  v.signal = child.signal, v.exit_status = child.exit_status;
  v.step = child.mark, v.out_of_memory = child.out_of_memory;
  v.wall_s = child.wall_s;
  if (!v.finished) return v;  // a crash or a hang is never a known failure
  v.error = s.error;
  v.judged = static_cast<VerdictClass>(s.judged);
  v.detail = s.detail;
  v.near_miss = s.near_miss != 0;
  const std::span<const MetricDef> table = metric_table();
  // A run that failed in the child measured nothing: its figures read 0 and its flags false, as
  // the stress JSON has always written them.
  for (std::size_t k = 0; k < table.size(); ++k) {
    v.metrics.push_back(s.measured[k] || !v.error.empty() ? std::optional<double>(s.metrics[k])
                                                          : std::nullopt);
  }
  v.ms_per_step = s.ms_per_step;
  v.known_failure = known_failure(engine, v.case_label, to_string(v.verdict()));
  v.expect_pass = s.expect_pass;
  v.degraded_steps = s.degraded_steps;
  for (std::uint32_t k = 0; k < s.counter_count && k < kMaxCounters; ++k)
    v.counters.push_back({s.counter_names[k], s.counter_columns[k], s.counters[k]});
  return v;
}

void print_stress_table(std::ostream& out, const std::vector<StressVerdict>& verdicts) {
  // The counters some engine gives a table column (registry.h), in the order they first appear.
  std::vector<std::string> columns;
  for (const StressVerdict& v : verdicts) {
    for (const StressVerdict::Counter& c : v.counters) {
      if (!c.column.empty() && std::find(columns.begin(), columns.end(), c.column) == columns.end())
        columns.push_back(c.column);
    }
  }
  auto counter_cell = [&](const StressVerdict& v, const std::string& title) {
    for (const StressVerdict::Counter& c : v.counters) {
      if (c.column == title) return fmt_g(c.value);
    }
    return std::string("-");
  };
  std::vector<std::string> header = {"case", "engine", "verdict"};
  for (const MetricDef& def : metric_table()) {
    if (def.outputs & kStressTable) header.push_back(def.column);
  }
  header.insert(header.end(), columns.begin(), columns.end());
  header.insert(header.end(), {"ms/step", "wall s", "why"});
  TextTable t(header);
  for (const StressVerdict& v : verdicts) {
    const bool done = v.finished && v.error.empty();
    std::string verdict = to_string(v.verdict());
    if (!v.known_failure.empty()) verdict += " (known)";
    std::vector<std::string> row = {v.case_label, v.engine.label(), verdict};
    const std::span<const MetricDef> table = metric_table();
    for (std::size_t k = 0; k < table.size(); ++k) {
      if (table[k].outputs & kStressTable)
        row.push_back(done ? metric_cell(table[k], v.metric(k)) : "-");
    }
    for (const std::string& column : columns)
      row.push_back(done ? counter_cell(v, column) : "-");
    row.insert(row.end(),
               {done ? fmt_ms(v.ms_per_step) : "-", fmt_g(v.wall_s, 3), v.verdict_detail()});
    t.add(row);
  }
  t.print(out);
  // Near misses (every failed check within a tenth of its tolerance) are tallied apart from clear
  // failures: a miss of 6e-8 m is not a miss of 2 m.
  std::map<std::string, int> by_verdict;
  for (const StressVerdict& v : verdicts)
    ++by_verdict[std::string(to_string(v.verdict())) + (v.near() ? " (near miss)" : "")];
  out << "\n" << verdicts.size() << " runs:";
  const char* sep = " ";
  for (const auto& [verdict, count] : by_verdict)
    out << sep << count << " " << verdict, sep = ", ";
  out << "\n";
  bool first = true;
  for (const StressVerdict& v : verdicts) {
    if (v.known_failure.empty()) continue;
    if (first) out << "known failures (reported, not counted in the exit status):\n";
    first = false;
    out << "  " << v.case_label << " in " << v.engine.label() << ": " << to_string(v.verdict())
        << "; " << v.known_failure << "\n";
  }
}

nlohmann::ordered_json stress_json(const std::vector<StressVerdict>& verdicts, bool quick,
                                   bool interrupted) {
  using nlohmann::ordered_json;
  ordered_json j;
  j["schema"] = "chainbench.stress/1";
  j["quick"] = quick;
  j["interrupted"] = interrupted;
  j["cases"] = ordered_json::array();
  for (const StressVerdict& v : verdicts) {
    ordered_json c;
    c["case"] = v.case_label;
    c["group"] = v.group;
    c["engine"] = v.engine.str();
    c["label"] = v.engine.label();
    c["verdict"] = to_string(v.verdict());
    c["detail"] = v.verdict_detail();
    c["stable"] = v.stable();
    c["fatal"] = v.fatal();
    if (!v.known_failure.empty()) c["known_failure"] = v.known_failure;
    c["finished"] = v.finished;
    const std::span<const MetricDef> table = metric_table();
    // The metrics the stress JSON shows (metric_table(): kStressJson): flags here, figures after
    // the counters, as the first stress JSON had them.
    auto metrics = [&](bool flags) {
      for (std::size_t k = 0; k < table.size(); ++k) {
        const MetricDef& def = table[k];
        if (!(def.outputs & kStressJson) || (def.kind == MetricKind::kFlag) != flags) continue;
        const std::optional<double> value = v.metric(k);
        c[def.json_key] = !value  ? nlohmann::ordered_json(nullptr)
                          : flags ? nlohmann::ordered_json(*value != 0.0)
                                  : json_number(*value);
      }
    };
    if (v.finished) {
      metrics(true);
      c["expect_pass"] = v.expect_pass;
      c["near_miss"] = v.near();
      c["degraded_steps"] = v.degraded_steps;
      nlohmann::ordered_json counters = nlohmann::ordered_json::object();
      for (const StressVerdict::Counter& c : v.counters)
        counters[c.name] = json_number(c.value);
      // The first stress JSON's two counters keep their keys: null for an engine without them.
      for (const char* legacy : {"budget_hits", "crush_events"})
        c[legacy] = counters.contains(legacy) ? counters[legacy] : nlohmann::ordered_json(nullptr);
      c["counters"] = std::move(counters);
      metrics(false);
      c["ms_per_step"] = json_number(v.ms_per_step);
    }
    if (v.signal) c["signal"] = v.signal;
    if (v.exit_status) c["exit_status"] = v.exit_status;
    if (!v.error.empty()) c["error"] = v.error;
    c["wall_s"] = v.wall_s;
    j["cases"].push_back(std::move(c));
  }
  return j;
}

}  // namespace chainbench
