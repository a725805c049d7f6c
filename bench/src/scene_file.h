// Scene files: the JSON format of DESIGN.md (schema 1), read with nlohmann-json.
#pragma once

#include "scene.h"

#include <string>

namespace chainbench {

// Reads and validates a scene file. On any problem throws InputError whose message lists every
// problem found as "FILE: JSON.path: reason", one per line.
Scene load_scene_file(const std::string& path);
// The same, from text already in memory; `source` names it in messages.
Scene parse_scene(const std::string& text, const std::string& source);

}  // namespace chainbench
