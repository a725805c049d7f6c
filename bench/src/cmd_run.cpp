// chainbench run: one scene in several engines, side by side.
#include "commands.h"
#include "input_error.h"
#include "output_file.h"
#include "progress.h"
#include "report.h"
#include "runner.h"
#include "scene_file.h"
#include "scene_library.h"

#include <iostream>
#include <memory>
#include <optional>

namespace chainbench {
namespace {

struct RunArgs {
  std::string scene;
  std::string scene_file;
  std::vector<std::string> sets;
  std::string engines = "chain,chain:variant=seed2014,box2d";
  std::string reference = "box2d";
  int steps = 0;
  std::string json, csv, trace;
  std::string metrics = "all";
};

int run(const RunArgs& a) {
  // Everything the user typed is checked before anything runs.
  Scene scene = a.scene_file.empty() ? make_scene(a.scene, a.sets) : load_scene_file(a.scene_file);
  if (!a.scene_file.empty() && !a.sets.empty())
    throw InputError("--set applies to built-in scenes, not --scene-file");
  if (a.steps > 0) scene.steps = a.steps;
  const std::vector<EngineSpec> engines = parse_engine_list(a.engines);
  std::optional<EngineSpec> reference;
  if (a.reference != "none") reference = parse_engine_spec(a.reference);
  RunOptions options;
  options.metrics = parse_metric_selection(a.metrics);
  auto json_out = open_output(a.json, "--json");
  auto csv_out = open_output(a.csv, "--csv");
  auto trace_out = open_output(a.trace, "--trace");
  std::optional<TraceWriter> trace;
  if (trace_out) {
    trace.emplace(*trace_out);
    options.trace = &*trace;
  }

  Progress progress;
  RunReport report;
  report.scene = &scene;
  auto run_one = [&](const EngineSpec& spec) {
    options.progress = [&](int done, int total) { progress.update(spec.str(), done, total); };
    EngineRun r = run_engine(scene, spec, options);
    progress.clear();
    return r;
  };
  for (const EngineSpec& spec : engines)
    report.runs.push_back(run_one(spec));
  if (reference) {
    report.reference_spec = reference->str();
    const bool included =
        std::any_of(report.runs.begin(), report.runs.end(),
                    [&](const EngineRun& r) { return r.engine == report.reference_spec; });
    if (!included) report.reference = run_one(*reference);
  }
  compare(report);

  print_run_table(std::cout, report);
  if (json_out) *json_out << run_json(report).dump(2) << '\n';
  if (csv_out) write_run_csv(*csv_out, report);
  finish_output(json_out.get(), a.json);
  finish_output(csv_out.get(), a.csv);
  finish_output(trace_out.get(), a.trace);
  return 0;
}

}  // namespace

void add_run_command(CLI::App& app, int* status) {
  auto args = std::make_shared<RunArgs>();
  CLI::App* run_app =
      app.add_subcommand("run", "Run one scene in several engines and compare them");
  auto* scene = run_app->add_option("--scene", args->scene, "built-in scene (chainbench list)");
  auto* file = run_app->add_option("--scene-file", args->scene_file, "scene file (JSON, schema 1)");
  scene->excludes(file);
  run_app->add_option("--set", args->sets, "KEY=VALUE parameter of a built-in scene (repeatable)");
  run_app
      ->add_option("--engines", args->engines, "engine specs, comma separated (chainbench engines)")
      ->capture_default_str();
  run_app
      ->add_option("--reference", args->reference, "engine the others are compared with, or none")
      ->capture_default_str();
  run_app->add_option("--steps", args->steps, "steps to run instead of the scene's")
      ->check(CLI::Range(1, 10'000'000));
  run_app->add_option("--json", args->json, "write the chainbench.run/1 JSON here");
  run_app->add_option("--csv", args->csv, "write one CSV row per engine here");
  run_app->add_option("--trace", args->trace,
                      "write every body's state after every step here (CSV)");
  run_app
      ->add_option("--metrics", args->metrics,
                   "all, none, or a comma list of displacement, penetration, stability")
      ->capture_default_str();
  run_app->callback([args, status, scene, file] {
    if (scene->count() == 0 && file->count() == 0)
      throw InputError("run: give --scene NAME or --scene-file FILE");
    *status = run(*args);
  });
}

}  // namespace chainbench
