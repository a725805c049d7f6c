// SPDX-License-Identifier: MIT
// `sweep --vary KEY=v1,v2,...`: one built-in scene built once for each value of one of its
// parameters (the time step first of all), so that error and cost can be read against it.
#pragma once

#include "model/scene.h"

#include <string>
#include <string_view>
#include <vector>

namespace chainbench {

struct SceneVary {
  std::string key;                 // a parameter every scene takes (chainbench list), e.g. "dt"
  std::vector<std::string> texts;  // each value as written: "1/30"
  std::vector<double> values;      // and as a number
};

// Parses "KEY=v1,v2,...", each value a number or a fraction "a/b" of two numbers. Throws
// InputError naming --vary for an empty key or value, a value given twice or one not a number.
SceneVary parse_vary(const std::string& text);

// Scene `name` built with `sets` and KEY = vary.values[k]. Varying dt with no steps in `sets`
// keeps the run's simulated time: steps = round(default steps * (1/60 s) / dt), at least 1.
// Throws InputError as make_scene does, and when `sets` gives KEY too.
Scene make_varied_scene(std::string_view name, const std::vector<std::string>& sets,
                        const SceneVary& vary, std::size_t k);

// Whether make_varied_scene sets each run's steps from its dt: dt varies and `sets` gives no steps.
bool keeps_simulated_time(const SceneVary& vary, const std::vector<std::string>& sets);

}  // namespace chainbench
