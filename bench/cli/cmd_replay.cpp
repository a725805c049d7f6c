// SPDX-License-Identifier: MIT
// chainbench replay: one scene in several engines, written as a page that plays them
// (replay_page.h); `run --replay FILE` writes the same page beside run's other outputs.
#include "cli/commands.h"
#include "cli/engine_choice.h"
#include "cli/run_scene.h"
#include "cli/value_checks.h"
#include "engines/registry.h"
#include "support/input_error.h"
#include "support/output_file.h"

#include <memory>

namespace chainbench {

void add_replay_command(CLI::App& app, int* status) {
  auto args = std::make_shared<RunArgs>();
  args->replay_option = "--out";
  // The size limit has one name, --replay-mb, as in `run`; --max-mb, its first name here, is
  // still read.
  args->replay_mb_option = "--replay-mb";
  CLI::App* r = app.add_subcommand(
      "replay", "Write one self-contained HTML page that plays every engine's run of a scene");
  auto* scene = r->add_option("--scene", args->scene, "built-in scene (chainbench list)");
  auto* file = r->add_option("--scene-file", args->scene_file, "scene file (JSON, schema 1)")
                   ->check(non_empty_path("scene file"));
  scene->excludes(file);
  r->add_option("--set", args->sets, "KEY=VALUE parameter of a built-in scene (repeatable)");
  r->add_option("--engines", args->engines,
                "engine specs, comma separated, \"defaults\" for the default list; default: " +
                    default_engine_list() + ", those that can run the scene")
      ->check(kEngineList);
  r->add_option("--reference", args->reference,
                "engine the chart measures the others from, or none; default: " +
                    default_reference().label());
  r->add_option("--steps", args->steps, "steps to run instead of the scene's")
      ->transform(whole_number_in(1, 10'000'000));
  r->add_option("--out", args->replay, "the page to write (HTML)")
      ->required()
      ->check(non_empty_path("output file"));
  r->add_option("--replay-mb,--max-mb", args->replay_mb,
                "the page's size limit, MB: beyond it only one step in k keeps its positions")
      ->capture_default_str()
      ->check(number_in(0.1, 10000.0));
  r->footer(
      "The page needs nothing beside it: open it in a browser, mail it, attach it to a bug "
      "report. Exit status: 0 written; 2 bad input or usage; 1 the page could not be written in "
      "full, or a plugin crashed or hung (the page shows the other engines); 130 Ctrl-C.");
  r->callback([args, status, scene, file] {
    if (scene->count() == 0 && file->count() == 0)
      throw InputError("replay: give --scene NAME or --scene-file FILE");
    refuse_clashing_files({{"--out", &args->replay}}, {{"--scene-file", &args->scene_file}});
    *status = run_scene(*args);
  });
}

}  // namespace chainbench
