#include "stress.h"

#include "child_process.h"
#include "report.h"
#include "runner.h"
#include "scene_library.h"
#include "text_table.h"

#include <cmath>
#include <cstdio>
#include <exception>
#include <map>

namespace chainbench {
namespace {

// What a child reports back through its pipe.
struct Summary {
  double max_penetration, peak_speed, speed_bound, ms_per_step, probe_x, target_x;
  std::uint64_t budget_hits, crush_events;
  std::uint8_t finite, in_bounds, blow_up;
  char error[240];
};

Summary summarize_case(const StressCase& c, const EngineSpec& engine) {
  Summary s{};
  try {
    const Scene scene = make_scene(c.scene, c.sets);
    const EngineRun run = run_engine(scene, engine, RunOptions{});
    const Metrics& m = run.metrics;
    s.max_penetration = *m.max_penetration;
    s.peak_speed = *m.peak_speed;
    s.speed_bound = *m.speed_bound;
    s.ms_per_step = run.timing.median_ms;
    s.finite = *m.finite, s.in_bounds = *m.in_bounds, s.blow_up = *m.blow_up;
    if (c.probe >= 0) {
      s.probe_x = run.final_positions[static_cast<std::size_t>(c.probe)].x;
      s.target_x = run.final_positions[static_cast<std::size_t>(c.target)].x;
    }
    if (run.chain) s.budget_hits = run.chain->budget_hits, s.crush_events = run.chain->crush_events;
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
  auto add = [&](const char* group, const char* scene, std::vector<std::string> sets, bool quick,
                 int probe = -1, int target = -1) {
    cases.push_back({group, scene, std::move(sets), quick, probe, target});
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
  for (const char* speed : {"10", "50", "100", "500"}) {
    add("fast body", "projectile", {std::string("speed=") + speed}, std::string(speed) == "100", 7,
        3);
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
  return cases;
}

bool StressVerdict::stable() const {
  return finished && finite && in_bounds && !blow_up && budget_hits == 0 && error.empty();
}

std::string StressVerdict::verdict() const {
  if (hang) return "hang";
  if (!finished && signal != 0) return "crash (signal " + std::to_string(signal) + ")";
  if (!finished) return "crash (exit " + std::to_string(exit_status) + ")";
  if (!error.empty()) return "error";
  std::string bad;
  if (!finite) bad += ", non-finite";
  if (!in_bounds) bad += ", out of bounds";
  if (blow_up) bad += ", blow-up";
  if (!bad.empty()) return "unstable: " + bad.substr(2);
  if (budget_hits > 0) return "budget";
  return "ok";
}

bool StressVerdict::fatal() const {
  return hang || !finished || !error.empty() || !finite || !in_bounds || blow_up;
}

StressVerdict run_stress_case(const StressCase& c, const EngineSpec& engine, double timeout_s) {
  StressVerdict v;
  v.case_label = c.label();
  v.group = c.group;
  v.engine = engine.str();
  Summary s{};
  const ChildOutcome child = run_in_child([&] { return summarize_case(c, engine); }, s, timeout_s);
  v.finished = child.finished, v.hang = child.hang;
  v.signal = child.signal, v.exit_status = child.exit_status;
  v.wall_s = child.wall_s;
  if (!v.finished) return v;
  v.error = s.error;
  v.max_penetration = s.max_penetration, v.peak_speed = s.peak_speed, v.speed_bound = s.speed_bound;
  v.ms_per_step = s.ms_per_step;
  v.finite = s.finite, v.in_bounds = s.in_bounds, v.blow_up = s.blow_up;
  v.budget_hits = s.budget_hits, v.crush_events = s.crush_events;
  // Beyond the stack's far face (x = 0.5) with the middle box still in place.
  v.tunnelled = c.probe >= 0 && s.probe_x > 0.6 && std::abs(s.target_x) < 0.25;
  return v;
}

void print_stress_table(std::ostream& out, const std::vector<StressVerdict>& verdicts) {
  TextTable t({"case", "engine", "stable", "verdict", "max pen m", "worst", "ms/step", "wall s"});
  for (const StressVerdict& v : verdicts) {
    std::string worst = "-";
    if (v.finished && v.error.empty()) {
      if (v.blow_up) {
        worst = "speed " + fmt_g(v.peak_speed) + " > " + fmt_g(v.speed_bound) + " m/s";
      } else if (v.tunnelled) {
        worst = "tunnelled";
      } else if (v.crush_events > 0) {
        worst = std::to_string(v.crush_events) + " crushes";
      }
    } else if (!v.error.empty()) {
      worst = v.error;
    }
    t.add({v.case_label, parse_engine_spec(v.engine).short_str(), v.stable() ? "yes" : "NO",
           v.verdict(), v.finished ? fmt_g(v.max_penetration) : "-", worst,
           v.finished ? fmt_ms(v.ms_per_step) : "-", fmt_g(v.wall_s, 3)});
  }
  t.print(out);
  std::map<std::string, int> by_verdict;
  int tunnelled = 0;
  for (const StressVerdict& v : verdicts) {
    const std::string verdict = v.verdict();
    ++by_verdict[verdict.substr(0, verdict.find(':'))];
    tunnelled += v.tunnelled;
  }
  out << "\n" << verdicts.size() << " runs:";
  const char* sep = " ";
  for (const auto& [verdict, count] : by_verdict)
    out << sep << count << " " << verdict, sep = ", ";
  out << "; tunnelling in " << tunnelled << "\n";
}

nlohmann::ordered_json stress_json(const std::vector<StressVerdict>& verdicts, bool quick) {
  using nlohmann::ordered_json;
  ordered_json j;
  j["schema"] = "chainbench.stress/1";
  j["quick"] = quick;
  j["cases"] = ordered_json::array();
  for (const StressVerdict& v : verdicts) {
    ordered_json c;
    c["case"] = v.case_label;
    c["group"] = v.group;
    c["engine"] = v.engine;
    c["label"] = parse_engine_spec(v.engine).short_str();
    c["verdict"] = v.verdict();
    c["stable"] = v.stable();
    c["fatal"] = v.fatal();
    c["finished"] = v.finished;
    if (v.finished) {
      c["finite"] = v.finite;
      c["in_bounds"] = v.in_bounds;
      c["blow_up"] = v.blow_up;
      c["tunnelled"] = v.tunnelled;
      c["budget_hits"] = v.budget_hits;
      c["crush_events"] = v.crush_events;
      c["max_penetration"] = json_number(v.max_penetration);
      c["peak_speed"] = json_number(v.peak_speed);
      c["speed_bound"] = json_number(v.speed_bound);
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
