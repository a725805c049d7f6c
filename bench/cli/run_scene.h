// SPDX-License-Identifier: MIT
// One scene in several engines, as `run` and `replay` both do it: what the user asked for, and
// the function that runs it, prints the table and writes the files asked for.
#pragma once

#include <string>
#include <vector>

namespace chainbench {

struct RunArgs {
  std::string scene;
  std::string scene_file;
  std::vector<std::string> sets;
  std::string engines;    // empty: every engine's defaults that can run the scene
  std::string reference;  // empty: the registry's reference engine
  int steps = 0;
  double timeout = 0.0;  // seconds an engine run in a child process (plugins) may take; 0: none
  std::string json, csv, trace;
  std::string trace_format = "dense";  // dense (with FILE.json beside it) or sparse
  std::string replay;                      // the replay page (replay_page.h), or empty
  const char* replay_option = "--replay";  // how the user named it, for messages
  double replay_mb = 20.0;                 // its size limit
  const char* replay_mb_option = "--replay-mb";
  std::string metrics = "all";
  std::vector<std::string> require;
  bool profile = false;  // print each engine's own timing of its step's stages
};

// Returns the exit status: 0; 3 when a --require engine fails; 1 when an engine run in a child
// process (a plugin) crashed or hung; 130 when Ctrl-C stopped it. Throws InputError for bad
// input before anything runs.
int run_scene(const RunArgs& args);

}  // namespace chainbench
