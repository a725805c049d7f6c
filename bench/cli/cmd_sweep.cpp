// SPDX-License-Identifier: MIT
// chainbench sweep: error against run time over a grid of engine settings.
#include "campaign/shard.h"
#include "campaign/sweep.h"
#include "cli/commands.h"
#include "cli/engine_choice.h"
#include "cli/interrupt.h"
#include "cli/progress.h"
#include "cli/value_checks.h"
#include "engines/registry.h"
#include "scenes/scene_file.h"
#include "scenes/scene_library.h"
#include "scenes/scene_vary.h"
#include "support/input_error.h"
#include "support/output_file.h"

#include <algorithm>
#include <iostream>
#include <memory>
#include <optional>

namespace chainbench {
namespace {

struct SweepArgs {
  std::vector<std::string> scenes, scene_files, sets, grids;
  std::string reference;  // empty: the registry's accurate reference
  int steps = 0;
  double timeout = 0.0;  // 0: none
  std::string json, csv;
  std::string shard;  // "K/N", or empty: the whole grid
  std::string vary;   // "KEY=v1,v2,...": each built-in scene once per value
};

int run(const SweepArgs& a) {
  // Everything the user typed is checked before anything runs.
  std::vector<Scene> scenes;
  std::vector<std::optional<SweepVariant>> variants;  // per scene: its --vary value
  std::vector<std::string> sets = a.sets, notes;
  if (a.steps > 0) sets.push_back("steps=" + std::to_string(a.steps));
  if (!a.vary.empty()) {
    if (a.scenes.empty()) throw InputError("--vary applies to built-in scenes: give --scene NAME");
    if (!a.scene_files.empty())
      throw InputError("--vary applies to built-in scenes, not --scene-file");
    const SceneVary vary = parse_vary(a.vary);
    for (const std::string& name : a.scenes) {
      for (std::size_t k = 0; k < vary.values.size(); ++k) {
        scenes.push_back(make_varied_scene(name, sets, vary, k));
        variants.push_back(SweepVariant{vary.key, vary.texts[k], vary.values[k]});
      }
    }
    if (keeps_simulated_time(vary, sets)) {
      notes.push_back(
          "--vary dt: each run lasts as long as the scene's default run at 1/60 s "
          "(steps = default steps / 60 / dt)");
    }
  } else {
    for (const std::string& name : a.scenes)
      scenes.push_back(make_scene(name, sets));
  }
  if (!a.scene_files.empty() && !a.sets.empty() && a.scenes.empty()) {
    throw InputError("--set applies to built-in scenes, not --scene-file");
  }
  for (const std::string& file : a.scene_files) {
    scenes.push_back(load_scene_file(file));
    if (a.steps > 0) {
      if (std::string note = set_run_length(scenes.back(), a.steps, file); !note.empty())
        notes.push_back(std::move(note));
    }
    if (std::string late = late_bodies_note(scenes.back(), file); !late.empty())
      notes.push_back(std::move(late));
  }
  variants.resize(scenes.size());
  if (scenes.empty())
    throw InputError("sweep: give --scene NAME or --scene-file FILE (repeatable)");
  std::vector<EngineSpec> grid;
  // A point given twice would be run and reported twice: refuse it, as run's --engines does.
  for (const std::string& g : a.grids) {
    for (EngineSpec& s : parse_grid(g)) {
      if (std::find(grid.begin(), grid.end(), s) != grid.end())
        throw InputError("--grid: point " + s.label() + " given twice");
      grid.push_back(std::move(s));
    }
  }
  const bool given = !grid.empty();
  if (!given) grid = default_sweep_grid();
  // Per scene, the points whose engine can run it: a given grid must fit every scene, the
  // default one leaves out what does not, with a note.
  std::vector<std::vector<EngineSpec>> grids(scenes.size());
  for (std::size_t k = 0; k < scenes.size(); ++k) {
    for (const EngineSpec& spec : grid) {
      const std::string why = missing_capability(spec, scenes[k]);
      if (why.empty()) {
        grids[k].push_back(spec);
      } else if (given) {
        throw InputError("--grid: scene " + scenes[k].name + ": " + why);
      } else {
        notes.push_back(spec.label() + " left out of scene " + scenes[k].name + ": " + why);
      }
    }
  }
  if (a.reference == "none") {
    throw InputError(
        "--reference none: a sweep measures each point's error against a reference "
        "run, so it needs one (leave --reference out for " +
        accurate_reference().label() + ")");
  }
  const EngineSpec reference =
      a.reference.empty() ? accurate_reference() : parse_engine_spec(a.reference);
  std::vector<EngineSpec> read = grid;
  read.push_back(reference);
  refuse_outputs_over_engine_files(read, {{"--json", &a.json}, {"--csv", &a.csv}});
  // Points are numbered over the scenes in the order they run; a shard runs its part of them.
  const Shard shard = a.shard.empty() ? Shard{} : parse_shard(a.shard);
  // A part is only of use merged, and merge reads the parts' JSON.
  if (!shard.whole() && a.json.empty())
    throw InputError("--shard " + a.shard + ": give --json FILE: a part is of use only to merge");
  std::string whole = "sweep\nreference " + reference.str() + "\n";
  std::vector<std::vector<bool>> include(scenes.size());
  std::vector<std::vector<std::size_t>> units(scenes.size());
  std::size_t next = 0;
  for (std::size_t k = 0; k < scenes.size(); ++k) {
    whole += "scene " + scene_identity(scenes[k]) + "\n";
    for (const EngineSpec& spec : grids[k]) {
      whole += spec.str() + "\n";
      include[k].push_back(shard.has(next));
      if (shard.has(next)) units[k].push_back(next);
      ++next;
    }
  }
  auto json_out = open_output(a.json, "--json");
  auto csv_out = open_output(a.csv, "--csv");

  std::optional<Interrupt> interrupt(std::in_place);
  Progress progress;
  std::vector<SweepResult> results;
  for (const Scene& scene : scenes) {
    const std::size_t k = static_cast<std::size_t>(&scene - scenes.data());
    SweepOptions options;
    options.stop = interrupt->flag();
    if (a.timeout > 0.0) options.timeout_s = a.timeout;
    options.include = include[k];
    const std::string name =
        variants[k] ? scene.name + " " + variants[k]->key + "=" + variants[k]->text : scene.name;
    options.progress = [&](const std::string& label, int done, int total) {
      progress.update(name + ": " + label, done, total);
    };
    results.push_back(sweep(scene, grids[k], reference, options));
    results.back().variant = variants[k];
    progress.clear();
    if (interrupt->stopped()) break;
  }
  const bool stopped = interrupt->stopped();
  interrupt.reset();
  if (stopped && std::all_of(results.begin(), results.end(),
                             [](const SweepResult& r) { return r.points.empty(); })) {
    // Nothing finished: every output keeps what it held (the temporaries go with their files).
    Interrupt::report("no point was measured, so the outputs are left as they were");
    return kInterruptedStatus;
  }

  for (const SweepResult& r : results) {
    print_sweep_table(std::cout, r);
    std::cout << '\n';
  }
  for (const std::string& note : notes)
    std::cout << "note: " << note << '\n';
  nlohmann::ordered_json json = sweep_json(results);
  if (!shard.whole()) {
    std::vector<std::size_t> ran;  // the units of the points measured, as the JSON lists them
    for (std::size_t k = 0; k < results.size(); ++k)
      ran.insert(ran.end(), units[k].begin(), units[k].begin() + results[k].points.size());
    json["shard"] =
        shard_json({"sweep", CHAINBENCH_VERSION, grid_fingerprint(whole), next}, shard, ran);
    std::cout << "note: part " << shard.index << "/" << shard.count << " of the grid, "
              << ran.size() << " of its " << next
              << " points; pareto marks compare these alone (chainbench merge marks the whole)\n";
  }
  if (json_out) json_out->stream() << json.dump(2) << '\n';
  if (csv_out) write_sweep_csv(csv_out->stream(), results);
  commit_outputs({json_out.get(), csv_out.get()});
  if (stopped) {
    Interrupt::report("the points measured so far are above (and in the outputs)");
    return kInterruptedStatus;
  }
  // A plugin that crashed or hung has its row; the sweep still fails.
  int status = 0;
  for (const SweepResult& r : results) {
    auto failed = [&](const EngineRun& run) {
      if (!run.failure) return;
      std::cerr << "chainbench: " << run.spec.label() << " on scene " << r.scene << ": "
                << *run.failure << "\n";
      status = 1;
    };
    if (r.reference_run) failed(*r.reference_run);
    for (const SweepPoint& p : r.points)
      failed(p.run);
  }
  return status;
}

}  // namespace

void add_sweep_command(CLI::App& app, int* status) {
  auto args = std::make_shared<SweepArgs>();
  CLI::App* sweep_app =
      app.add_subcommand("sweep", "Error against run time over a grid of engine settings");
  sweep_app->add_option("--scene", args->scenes, "built-in scene (repeatable)");
  sweep_app->add_option("--scene-file", args->scene_files, "scene file (repeatable)")
      ->check(non_empty_path("scene file"));
  sweep_app->add_option("--set", args->sets, "KEY=VALUE for every built-in scene (repeatable)");
  sweep_app->add_option("--grid", args->grids,
                        "NAME:key=v1,v2;key=v3,... every combination (repeatable); "
                        "default: one setting at a time around each engine's defaults");
  sweep_app->add_option(
      "--reference", args->reference,
      "engine the points are measured against, unless the scene has expectations; "
      "default: " +
          accurate_reference().label());
  sweep_app->add_option("--steps", args->steps, "steps to run instead of each scene's")
      ->transform(whole_number_in(1, 10'000'000));
  sweep_app
      ->add_option("--timeout", args->timeout,
                   "seconds a point of a plugin (run in a child process) may take before it "
                   "counts as a hang; default: no limit")
      ->check(timeout_seconds());
  sweep_app->add_option("--json", args->json, "write the chainbench.sweep/1 JSON here")
      ->check(non_empty_path("output file"));
  sweep_app->add_option("--csv", args->csv, "write one CSV row per point here")
      ->check(non_empty_path("output file"));
  sweep_app->add_option("--vary", args->vary,
                        "KEY=v1,v2,...: run each --scene once per value of its parameter KEY "
                        "(values may be fractions: dt=1/30,1/60,1/120,1/240)");
  sweep_app
      ->add_option("--shard", args->shard,
                   "K/N: run the K-th of N parts of the grid (points K, K+N, ...); "
                   "chainbench merge joins the parts' JSON")
      ->check(non_empty_text("--shard", "K/N"));
  sweep_app->callback([args, status] {
    std::vector<NamedFile> inputs;
    for (const std::string& file : args->scene_files)
      inputs.emplace_back("--scene-file", &file);
    refuse_clashing_files({{"--json", &args->json}, {"--csv", &args->csv}}, inputs);
    *status = run(*args);
  });
}

}  // namespace chainbench
