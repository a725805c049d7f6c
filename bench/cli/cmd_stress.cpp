// SPDX-License-Identifier: MIT
// chainbench stress: the stiff and extreme cases, in every engine, with verdicts.
#include "campaign/shard.h"
#include "campaign/stress.h"
#include "cli/commands.h"
#include "cli/engine_choice.h"
#include "cli/interrupt.h"
#include "cli/progress.h"
#include "cli/value_checks.h"
#include "engines/plugin_load.h"
#include "engines/registry.h"
#include "scenes/scene_library.h"
#include "support/input_error.h"
#include "support/output_file.h"

#include <algorithm>
#include <exception>
#include <iostream>
#include <map>
#include <memory>
#include <optional>

namespace chainbench {
namespace {

struct StressArgs {
  bool quick = false;
  std::string engines;  // empty: every engine's defaults
  std::string filter;
  double timeout = 120.0;
  std::string json;
  std::string shard;  // "K/N", or empty: the whole matrix
};

// Everything the matrix's verdicts depend on: each case's scene, every engine, the timeout.
std::string describe_matrix(const std::vector<StressCase>& cases,
                            const std::vector<EngineSpec>& engines, double timeout) {
  std::string whole = "stress\ntimeout " + std::to_string(timeout) + "\n";
  for (const StressCase& c : cases) {
    std::string scene;
    try {
      scene = scene_identity(make_scene(c.scene, c.sets));
    } catch (const std::exception& e) {
      scene = e.what();  // the case reports it as its error verdict
    }
    whole += "case " + c.label() + " " + scene + "\n";
  }
  for (const EngineSpec& e : engines)
    whole += "engine " + e.str() + "\n";
  return whole;
}

int run(const StressArgs& a) {
  // A plugin that dies while it loads is a crash row in each of its cases, not the end of the
  // matrix (plugin_engine.h).
  keep_plugins_that_fail_to_load(true);
  const std::vector<EngineSpec> engines =
      a.engines.empty() ? default_engines() : parse_engine_list(a.engines);
  refuse_outputs_over_engine_files(engines, {{"--json", &a.json}});
  // Substrings rather than a regular expression: std::regex is slow to build and GCC 12 warns
  // inside it under the sanitizers.
  std::vector<std::string> wanted;
  for (std::size_t at = 0; at <= a.filter.size();) {
    const std::size_t bar = std::min(a.filter.find('|', at), a.filter.size());
    if (bar > at) wanted.push_back(a.filter.substr(at, bar - at));
    at = bar + 1;
  }
  auto selected = [&](const std::string& label) {
    return wanted.empty() || std::any_of(wanted.begin(), wanted.end(), [&](const std::string& w) {
             return label.find(w) != std::string::npos;
           });
  };
  const auto json_out = open_output(a.json, "--json");
  std::vector<StressCase> cases;
  for (const StressCase& c : stress_cases()) {
    if ((!a.quick || c.quick) && selected(c.label())) cases.push_back(c);
  }
  if (cases.empty()) throw InputError("stress: no case matches --filter \"" + a.filter + "\"");
  // Runs are numbered case by case, engine by engine; a shard runs its part of them.
  const Shard shard = a.shard.empty() ? Shard{} : parse_shard(a.shard);
  // A part is only of use merged, and merge reads the parts' JSON.
  if (!shard.whole() && a.json.empty())
    throw InputError("--shard " + a.shard + ": give --json FILE: a part is of use only to merge");
  const std::size_t units = cases.size() * engines.size();
  std::vector<std::size_t> ran;
  for (std::size_t u = 0; u < units; ++u) {
    if (shard.has(u)) ran.push_back(u);
  }

  Progress progress;
  std::vector<StressVerdict> verdicts;
  int done = 0;
  // Ctrl-C stops the run under way; the runs that finished are reported and written.
  std::optional<Interrupt> interrupt(std::in_place);
  for (const std::size_t u : ran) {
    const StressCase& c = cases[u / engines.size()];
    const EngineSpec& e = engines[u % engines.size()];
    progress.update(c.label() + " / " + e.label(), done++, static_cast<int>(ran.size()));
    StressVerdict v = run_stress_case(c, e, a.timeout, interrupt->flag());
    if (v.interrupted || interrupt->stopped()) break;
    verdicts.push_back(std::move(v));
  }
  progress.clear();
  const bool stopped = interrupt->stopped();
  interrupt.reset();
  if (stopped && verdicts.empty()) {
    // Nothing finished: every output keeps what it held (the temporaries go with their files).
    Interrupt::report("no run finished, so the outputs are left as they were");
    return kInterruptedStatus;
  }
  ran.resize(verdicts.size());  // a part names the runs it holds
  if (verdicts.empty() && !stopped) {
    std::cout << "part " << shard.index << "/" << shard.count << " holds none of the " << units
              << " runs\n";
  } else {
    print_stress_table(std::cout, verdicts);
  }
  nlohmann::ordered_json json = stress_json(verdicts, a.quick, stopped);
  if (!shard.whole()) {
    const ShardOrigin origin{"stress", CHAINBENCH_VERSION,
                             grid_fingerprint(describe_matrix(cases, engines, a.timeout)), units};
    json["shard"] = shard_json(origin, shard, ran);
  }
  if (json_out) json_out->stream() << json.dump(2) << '\n';
  commit_outputs({json_out.get()});
  if (std::none_of(engines.begin(), engines.end(),
                   [](const EngineSpec& e) { return is_gate(e); })) {
    std::cerr << "chainbench: note: no engine in the list gates the run (the modern chain solver "
                 "does): the exit status judges nothing\n";
  }
  if (stopped) {
    Interrupt::report("the runs that finished are above (and in the outputs)");
    return kInterruptedStatus;
  }
  std::map<std::string, int> failures;  // per gate engine (registry.h)
  for (const StressVerdict& v : verdicts)
    failures[v.engine.label()] += v.fatal();
  int status = 0;
  for (const std::string& why : plugins_that_failed_to_load()) {
    std::cerr << "chainbench: " << why << " (its rows say crash; the other engines ran)\n";
    status = 1;
  }
  // A plugin that crashed, hung or failed is a fault of the command's own inputs, as in run and
  // sweep, whatever gates the build.
  std::map<std::string, int> plugin_faults;
  for (const StressVerdict& v : verdicts) {
    if (engine_def(v.engine.engine).isolated && v.skipped.empty() &&
        (!v.finished || !v.error.empty()))
      ++plugin_faults[v.engine.label()];
  }
  for (const auto& [label, count] : plugin_faults) {
    std::cerr << "chainbench: " << label << " crashed, hung or failed on " << count
              << " stress case(s) (its rows say which)\n";
    status = 1;
  }
  for (const auto& [label, count] : failures) {
    if (count == 0) continue;
    std::cerr << "chainbench: " << label << " is not ok on " << count << " stress case(s)\n";
    status = 1;
  }
  return status;
}

}  // namespace

void add_stress_command(CLI::App& app, int* status) {
  auto args = std::make_shared<StressArgs>();
  CLI::App* s = app.add_subcommand(
      "stress", "The stiff and extreme cases, each in every engine, with verdicts");
  s->add_flag("--quick", args->quick, "the CI subset: one case of each kind, small");
  s->add_option("--engines", args->engines,
                "engine specs, comma separated; default: " + default_engine_list())
      ->check(kEngineList);
  s->add_option("--filter", args->filter,
                "run only the cases whose label contains one of these |-separated texts");
  s->add_option("--timeout", args->timeout, "seconds a case may take before it counts as a hang")
      ->capture_default_str()
      ->check(timeout_seconds());
  s->add_option("--json", args->json, "write the chainbench.stress/1 JSON here")
      ->check(non_empty_path("output file"));
  s->add_option("--shard", args->shard,
                "K/N: run the K-th of N parts of the matrix (runs K, K+N, ...); chainbench merge "
                "joins the parts' JSON")
      ->check(non_empty_text("--shard", "K/N"));
  s->footer(
      "Verdicts, worst first: crash, hang, error, unstable, escaped, tunnelled, wrong, "
      "penetrating, budget, ok (skipped: the engine cannot do what the case needs).\nExit status 1 "
      "when an engine that gates the build (the modern chain solver) is anything but ok or budget "
      "on a case that is not one of its listed known failures, or when a plugin crashed, hung or "
      "failed on a case; other engines' verdicts are reported only.");
  s->callback([args, status] { *status = run(*args); });
}

}  // namespace chainbench
