// SPDX-License-Identifier: MIT
// chainbench run: one scene in several engines, side by side.
#include "cli/commands.h"
#include "cli/engine_choice.h"
#include "cli/interrupt.h"
#include "cli/progress.h"
#include "cli/run_scene.h"
#include "cli/value_checks.h"
#include "judge/verdict.h"
#include "output/replay_page.h"
#include "output/replay_recorder.h"
#include "output/report.h"
#include "output/stage_table.h"
#include "output/trace_writer.h"
#include "run/runner.h"
#include "scenes/scene_file.h"
#include "scenes/scene_library.h"
#include "support/input_error.h"
#include "support/output_file.h"
#include "support/text_table.h"

#include <algorithm>
#include <iostream>
#include <memory>
#include <optional>

namespace chainbench {
namespace {

// What keeps a required engine's run from passing: each expectation it missed and a verdict
// other than ok. Empty when it passes.
std::vector<std::string> shortfalls(const EngineRun& run) {
  std::vector<std::string> out;
  if (!run.verdict) return out;
  for (const Finding& f : run.verdict->findings)
    out.push_back(std::string(to_string(f.what)) + ": " + f.detail);
  return out;
}

}  // namespace

int run_scene(const RunArgs& a) {
  // Everything the user typed is checked before anything runs. A built-in scene is built for the
  // run's length, so that its right answer follows it.
  if (!a.scene_file.empty() && !a.sets.empty())
    throw InputError("--set applies to built-in scenes, not --scene-file");
  std::vector<std::string> sets = a.sets;
  if (a.steps > 0) sets.push_back("steps=" + std::to_string(a.steps));
  Scene scene = a.scene_file.empty() ? make_scene(a.scene, sets) : load_scene_file(a.scene_file);
  std::string note;
  if (!a.scene_file.empty() && a.steps > 0) note = set_run_length(scene, a.steps, a.scene_file);
  if (!a.scene_file.empty()) {
    if (std::string late = late_bodies_note(scene, a.scene_file); !late.empty())
      note += (note.empty() ? "" : "\nnote: ") + late;
  }
  const EngineChoice choice = choose_engines(a.engines, {&scene});
  const std::vector<EngineSpec>& engines = choice.engines;
  std::optional<EngineSpec> reference;
  if (a.reference != "none") {
    reference = a.reference.empty() ? default_reference() : parse_engine_spec(a.reference);
    if (std::string why = missing_capability(*reference, scene); !why.empty()) {
      if (!a.reference.empty()) throw InputError("--reference: scene " + scene.name + ": " + why);
      reference.reset();  // the default reference cannot run this scene: compare with none
    }
  }
  std::vector<EngineSpec> required;
  for (const std::string& text : a.require) {
    EngineSpec spec = parse_engine_spec(text);
    if (std::find(engines.begin(), engines.end(), spec) == engines.end()) {
      // A default the scene rules out: say why, not merely that it is missing.
      for (const auto& [out, why] : choice.left_out) {
        if (out == spec)
          throw InputError("--require " + text + ": left out of the default engines, " + why);
      }
      throw InputError("--require " + text + ": not among the engines run (" +
                       (a.engines.empty() ? default_engine_list() : a.engines) + ")");
    }
    if (std::find(required.begin(), required.end(), spec) == required.end())
      required.push_back(std::move(spec));
  }
  RunOptions options;
  options.metrics = parse_metric_selection(a.metrics);
  options.isolate = true;  // a plugin that dies is its row's crash, not the end of the run
  options.stages = a.profile;
  if (a.timeout > 0.0) options.timeout_s = a.timeout;
  std::vector<EngineSpec> read = engines;
  if (reference) read.push_back(*reference);
  refuse_outputs_over_engine_files(
      read,
      {{"--json", &a.json}, {"--csv", &a.csv}, {"--trace", &a.trace}, {"--replay", &a.replay}});
  if (!required.empty()) {
    // A verdict needs stability and penetration.
    options.metrics.stability = options.metrics.penetration = true;
  }
  if (!a.replay.empty()) {
    check_replay_size(scene);
    options.metrics = MetricSelection{};  // the page marks every failed check
  }
  auto json_out = open_output(a.json, "--json");
  auto csv_out = open_output(a.csv, "--csv");
  auto trace_out = open_output(a.trace, "--trace");
  const bool dense = a.trace_format == "dense";
  // The dense trace's metadata goes beside it, FILE.json, unless the trace goes to a device or a
  // pipe (written directly): there is no file to be beside then.
  const bool trace_is_file = trace_out && trace_out->written() >= 0;
  std::unique_ptr<OutputFile> trace_meta_out;
  if (trace_is_file && dense)
    trace_meta_out = open_output(trace_metadata_path(a.trace), "--trace's metadata");
  // Notes about the trace go to whichever of the command's streams the trace is not.
  std::ostream& trace_note =
      trace_out && trace_out->shared_stream() == &std::cerr ? std::cout : std::cerr;
  if (trace_out && dense && !trace_meta_out) {
    trace_note << "chainbench: note: --trace " << a.trace
               << " is written directly (a device, a pipe or the command's own output): its "
                  "metadata (dt, the engines' specs, the units) is not written; the rows' time "
                  "column holds step * dt\n";
  }
  auto replay_out = open_output(a.replay, a.replay_option);
  std::optional<TraceWriter> trace;
  long long trace_kept = -1;  // the trace's bytes up to the end of the last engine that finished
  if (trace_out) {
    trace.emplace(trace_out->stream(), scene, dense ? TraceFormat::kDense : TraceFormat::kSparse);
    options.observers.push_back(&*trace);
    trace_kept = trace_out->written();
  }
  std::optional<ReplayRecorder> replay;
  if (replay_out) {
    replay.emplace(scene, reference);
    options.observers.push_back(&*replay);
  }

  Progress progress;
  RunReport report;
  report.scene = &scene;
  // Ctrl-C stops the run under way; the engines that finished are reported and written.
  std::optional<Interrupt> interrupt(std::in_place);
  options.stop = interrupt->flag();
  auto run_one = [&](const EngineSpec& spec) -> std::optional<EngineRun> {
    if (interrupt->stopped()) return std::nullopt;
    // The label the table uses, not the canonical spec: that one fills the line with defaults.
    const std::string label = scene.name + ": " + spec.label();
    options.progress = [&](int done, int total) { progress.update(label, done, total); };
    // Drawn here first: a plugin's bar is drawn by its child process, and cleared here.
    progress.update(label, 0, scene.steps);
    EngineRun r = run_engine(scene, spec, options);
    progress.clear();
    if (r.interrupted) return std::nullopt;  // a half run says nothing
    if (trace_out) {
      trace_kept = trace_out->written();
      trace->finished();
    }
    return r;
  };
  // A replay measures every engine from the reference at every step, so the reference runs
  // first; the report keeps the engines in the order given.
  const bool included =
      reference && std::find(engines.begin(), engines.end(), *reference) != engines.end();
  if (reference) report.reference_spec = *reference;
  if (reference && !included && a.reference.empty()) {
    // It may cost more than the engines asked for: say so, and how to leave it out.
    std::cerr << "chainbench: note: the reference " << reference->label()
              << " is not among --engines and runs too (--reference none skips it)\n";
  }
  if (reference && !included && replay) report.reference = run_one(*reference);
  std::vector<std::optional<EngineRun>> runs(engines.size());
  for (int pass = 0; pass < 2; ++pass) {
    for (std::size_t k = 0; k < engines.size(); ++k) {
      const bool first = replay && reference && engines[k] == *reference;
      if ((pass == 0) == first) runs[k] = run_one(engines[k]);
    }
  }
  for (std::optional<EngineRun>& r : runs) {
    if (r) report.runs.push_back(std::move(*r));
  }
  if (reference && !included && !replay) report.reference = run_one(*reference);
  report.interrupted = interrupt->stopped();
  interrupt.reset();
  if (report.interrupted && report.runs.empty() && !report.reference) {
    // Nothing finished: every output keeps what it held (the temporaries go with their files).
    Interrupt::report("no engine finished, so the outputs are left as they were");
    return kInterruptedStatus;
  }
  if (report.interrupted && trace_out && !trace_out->cut_back(trace_kept)) {
    // Written directly (a pipe): the rows of the run cut short are there; say where they start
    // (in the sparse form's comments; the dense form holds rows only).
    if (dense) {
      trace_note << "chainbench: note: --trace " << a.trace
                 << " was written directly: its last engine's rows are of a run that did not "
                    "finish\n";
    } else {
      trace_out->stream() << "# interrupted: the rows after the last finished engine's are of an "
                             "engine that did not finish\n";
    }
  }
  if (trace_meta_out) {
    trace_meta_out->stream()
        << trace_metadata_json(scene, trace->finished_engines(), report.interrupted).dump(2)
        << '\n';
  }
  compare(report);

  print_run_table(std::cout, report);
  if (a.profile) print_stage_table(std::cout, report);
  if (!note.empty()) std::cout << "\nnote: " << note << '\n';
  for (const std::string& left_out : choice.notes)
    std::cout << "note: " << left_out << '\n';
  if (json_out) json_out->stream() << run_json(report).dump(2) << '\n';
  if (csv_out) write_run_csv(csv_out->stream(), report);
  ReplayPageSummary written;
  if (replay_out) {
    ReplayPageOptions page;
    page.generator = "chainbench " CHAINBENCH_VERSION;
    page.max_bytes = static_cast<std::size_t>(a.replay_mb * 1e6);
    page.limit_option = a.replay_mb_option;
    // Too big a page throws; the outputs are then left as they were.
    written = write_replay_page(replay_out->stream(), report, *replay, page);
  }
  commit_outputs(
      {json_out.get(), csv_out.get(), trace_out.get(), trace_meta_out.get(), replay_out.get()});
  // A sparse trace over an earlier dense one: the earlier one's metadata would describe another
  // run.
  if (trace_is_file && !dense && remove_trace_metadata(trace_metadata_path(a.trace)))
    std::cerr << "chainbench: note: removed " << trace_metadata_path(a.trace)
              << ", the metadata of the dense trace this sparse one replaced\n";
  if (replay_out) {
    std::cout << "replay: wrote " << a.replay << " (" << fmt_g(written.bytes / 1e6, 3)
              << " MB; centres to " << fmt_g(written.quantum, 3) << " m, "
              << (written.stride == 1 ? std::string("every step")
                                      : "one step in " + std::to_string(written.stride))
              << ")\n";
  }
  if (report.interrupted) {
    Interrupt::report("the engines that finished are above (and in the outputs)");
    return kInterruptedStatus;
  }
  int status = 0;
  if (!required.empty() && scene.expect.empty()) {
    std::cerr << "chainbench: note: the scene states no expectations here; --require judges the "
                 "verdict alone\n";
  }
  for (const EngineSpec& spec : required) {
    const auto run = std::find_if(report.runs.begin(), report.runs.end(),
                                  [&](const EngineRun& r) { return r.spec == spec; });
    for (const std::string& why : shortfalls(*run)) {
      std::cerr << "chainbench: required engine " << spec.label() << " fails: " << why << '\n';
      status = 3;
    }
  }
  // A plugin that crashed or hung has its row; the others' results are kept, and the run fails.
  auto failed = [&](const EngineRun& r) {
    if (!r.failure) return;
    std::cerr << "chainbench: " << r.spec.label() << " " << *r.failure << " (its row says "
              << to_string(r.verdict->worst) << "; the other engines' results are kept)\n";
    if (status == 0) status = 1;
  };
  for (const EngineRun& r : report.runs)
    failed(r);
  if (report.reference) failed(*report.reference);
  return status;
}

void add_run_command(CLI::App& app, int* status) {
  auto args = std::make_shared<RunArgs>();
  CLI::App* run_app =
      app.add_subcommand("run", "Run one scene in several engines and compare them");
  auto* scene = run_app->add_option("--scene", args->scene, "built-in scene (chainbench list)");
  auto* file = run_app->add_option("--scene-file", args->scene_file, "scene file (JSON, schema 1)")
                   ->check(non_empty_path("scene file"));
  scene->excludes(file);
  run_app->add_option("--set", args->sets, "KEY=VALUE parameter of a built-in scene (repeatable)");
  run_app
      ->add_option("--engines", args->engines,
                   "engine specs, comma separated (chainbench engines), \"defaults\" for the "
                   "default list (defaults,box2d:sleep=1 adds one); default: " +
                       default_engine_list() + ", those that can run the scene")
      ->check(kEngineList);
  run_app->add_option(
      "--reference", args->reference,
      "engine the others are compared with, or none; default: " + default_reference().label());
  run_app->add_option("--steps", args->steps, "steps to run instead of the scene's")
      ->transform(whole_number_in(1, 10'000'000));
  run_app
      ->add_option("--timeout", args->timeout,
                   "seconds a plugin's run (in a child process) may take before it counts as a "
                   "hang, 0.001 to 86400; default: no limit")
      ->check(timeout_seconds());
  run_app->add_option("--json", args->json, "write the chainbench.run/1 JSON here")
      ->check(non_empty_path("output file"));
  run_app->add_option("--csv", args->csv, "write one CSV row per engine here")
      ->check(non_empty_path("output file"));
  auto* trace =
      run_app
          ->add_option("--trace", args->trace,
                       "write every body's state after every step here (CSV; dense: its metadata "
                       "goes beside it, FILE.json)")
          ->check(non_empty_path("output file"));
  run_app
      ->add_option("--trace-format", args->trace_format,
                   "dense: a row per engine, step and body, as pandas reads it; sparse: a body's "
                   "row only when it changed, for huge scenes")
      ->capture_default_str()
      ->needs(trace)
      ->check(CLI::IsMember({"dense", "sparse"}));
  auto* replay = run_app
                     ->add_option("--replay", args->replay,
                                  "write a page that plays every engine's run here (HTML, "
                                  "self-contained)")
                     ->check(non_empty_path("output file"));
  run_app->add_option("--replay-mb", args->replay_mb, "the replay page's size limit, MB")
      ->capture_default_str()
      ->needs(replay)
      ->check(number_in(0.1, 10000.0));
  run_app
      ->add_option("--metrics", args->metrics,
                   "all, none, or a comma list of displacement, penetration, stability")
      ->capture_default_str();
  run_app->add_option("--require", args->require,
                      "engine spec that must meet every expectation with verdict ok, else exit "
                      "3 (repeatable)");
  run_app->add_flag("--profile", args->profile,
                    "after the table, each engine's step split into the stages it times itself "
                    "(chain, box2d, box2d3; mean ms per step; also stages_ms in the JSON)");
  run_app->footer(
      "Exit status: 0 done; 2 bad input or usage; 3 a --require engine missed an expectation or "
      "was not ok; 1 a plugin crashed, hung or failed a step (its row says so; the other engines' "
      "results are kept), an output could not be finished, or an internal failure; 130 Ctrl-C (the "
      "engines "
      "that finished are kept).");
  run_app->callback([args, status, scene, file] {
    if (scene->count() == 0 && file->count() == 0)
      throw InputError("run: give --scene NAME or --scene-file FILE");
    const std::string trace_meta = args->trace.empty() || args->trace_format != "dense"
                                       ? std::string()
                                       : trace_metadata_path(args->trace);
    refuse_clashing_files({{"--json", &args->json},
                           {"--csv", &args->csv},
                           {"--trace", &args->trace},
                           {"--trace's metadata", &trace_meta},
                           {"--replay", &args->replay}},
                          {{"--scene-file", &args->scene_file}});
    *status = run_scene(*args);
  });
}

}  // namespace chainbench
