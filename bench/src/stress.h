// The stiff and extreme cases of `chainbench stress`: a matrix of scenes, each run in every
// engine in a child process of its own (a crash or a hang is a verdict, not the end of the
// run), each judged by the stability metrics, penetration and wall time.
#pragma once

#include "engine_spec.h"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

namespace chainbench {

struct StressCase {
  std::string group;  // what the case varies: "mass ratio", "time step", "squeeze" ...
  std::string scene;  // a built-in scene
  std::vector<std::string> sets;
  bool quick = false;  // part of --quick
  // Tunnelling: the projectile `probe` ends beyond the stack while the box `target` in its path
  // never moved. A projectile that knocks its target out also ends beyond the stack, legitimately.
  int probe = -1;
  int target = -1;
  std::string label() const;  // "push_into_wall n=10000"
};

// The full matrix; cases with quick = true form --quick.
std::vector<StressCase> stress_cases();

struct StressVerdict {
  std::string case_label, group, engine;
  bool finished = false;  // false: the child crashed or ran out of time
  bool hang = false;
  int signal = 0;       // the signal that ended the child, if one did
  int exit_status = 0;  // or its exit status, if it exited without a result
  bool finite = true, in_bounds = true, blow_up = false, tunnelled = false;
  std::uint64_t budget_hits = 0, crush_events = 0;
  double max_penetration = 0.0, peak_speed = 0.0, speed_bound = 0.0;
  double ms_per_step = 0.0, wall_s = 0.0;
  std::string error;  // the run failed with an exception in the child

  bool stable() const;
  // ok / unstable: non-finite, out of bounds, blow-up / budget / hang / crash (signal N) /
  // crash (exit N) / error
  std::string verdict() const;
  // Whether this verdict, on the modern solver, fails the stress run.
  bool fatal() const;
};

// Runs one case in one engine in a child process, killed after `timeout_s` seconds.
StressVerdict run_stress_case(const StressCase& c, const EngineSpec& engine, double timeout_s);

void print_stress_table(std::ostream& out, const std::vector<StressVerdict>& verdicts);
nlohmann::ordered_json stress_json(const std::vector<StressVerdict>& verdicts, bool quick);

}  // namespace chainbench
