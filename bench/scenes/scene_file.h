// SPDX-License-Identifier: MIT
// Scene files: the JSON format of docs/scene-format.md (schema 1), read with nlohmann-json.
#pragma once

#include "model/scene.h"

#include <string>

namespace chainbench {

// Reads and validates a scene file. On any problem throws InputError whose message lists every
// problem found as "FILE: JSON.path: reason", one per line.
Scene load_scene_file(const std::string& path);
// The same, from text already in memory; `source` names it in messages.
Scene parse_scene(const std::string& text, const std::string& source);

// Runs a scene file's scene for `steps` steps instead of its own. Expectations stated for its last
// step say nothing about another one and are dropped (the returned note says how many); windowed
// ones are kept, and a window beyond `steps` is refused (InputError naming the entry).
std::string set_run_length(Scene& scene, int steps, const std::string& source);

// A note when bodies of the scene enter only after its last step (from_step >= steps: valid, as
// a file may be run longer with --steps, but they take part in nothing); empty otherwise.
std::string late_bodies_note(const Scene& scene, const std::string& source);

}  // namespace chainbench
