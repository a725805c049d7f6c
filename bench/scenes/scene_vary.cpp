// SPDX-License-Identifier: MIT
#include "scenes/scene_vary.h"
#include "support/number_text.h"

#include "scenes/scene_library.h"
#include "support/input_error.h"

#include <algorithm>
#include <charconv>
#include <cmath>

namespace chainbench {
namespace {

double parse_value(const std::string& what, const std::string& text) {
  const std::size_t slash = text.find('/');
  if (slash == std::string::npos) return parse_number(what, text);
  const double num = parse_number(what, text.substr(0, slash));
  const double den = parse_number(what, text.substr(slash + 1));
  if (den == 0.0) throw InputError(what + ": \"" + text + "\" divides by zero");
  const double v = num / den;
  if (!std::isfinite(v)) throw InputError(what + ": \"" + text + "\" is not a finite number");
  return v;
}

}  // namespace

SceneVary parse_vary(const std::string& text) {
  const std::size_t eq = text.find('=');
  if (eq == std::string::npos || eq == 0)
    throw InputError("--vary \"" + text + "\": expected KEY=v1,v2,... (such as dt=1/30,1/60)");
  SceneVary vary;
  vary.key = text.substr(0, eq);
  const std::string what = "--vary " + vary.key;
  std::size_t begin = eq + 1;
  while (true) {
    const std::size_t comma = std::min(text.find(',', begin), text.size());
    std::string value = text.substr(begin, comma - begin);
    if (value.empty()) throw InputError(what + ": an empty value in \"" + text + "\"");
    const double v = parse_value(what, value);
    if (std::find(vary.values.begin(), vary.values.end(), v) != vary.values.end())
      throw InputError(what + ": value " + value + " given twice");
    vary.texts.push_back(std::move(value));
    vary.values.push_back(v);
    if (comma == text.size()) break;
    begin = comma + 1;
  }
  return vary;
}

namespace {

// `sets` gives `key` a value ("key=...").
bool sets_key(const std::vector<std::string>& sets, const std::string& key) {
  return std::any_of(sets.begin(), sets.end(), [&](const std::string& kv) {
    return kv.compare(0, key.size() + 1, key + "=") == 0;
  });
}

}  // namespace

bool keeps_simulated_time(const SceneVary& vary, const std::vector<std::string>& sets) {
  return vary.key == "dt" && !sets_key(sets, "steps");
}

Scene make_varied_scene(std::string_view name, const std::vector<std::string>& sets,
                        const SceneVary& vary, std::size_t k) {
  if (sets_key(sets, vary.key))
    throw InputError("--vary " + vary.key + ": --set " + vary.key + " gives it a single value too");
  const SceneRecipe* recipe = find_recipe(name);
  if (!recipe) return make_scene(name, sets);  // refused there, naming the scenes
  const std::vector<SceneParam> params = all_params(*recipe);
  const auto p = std::find_if(params.begin(), params.end(),
                              [&](const SceneParam& q) { return q.key == vary.key; });
  if (p == params.end()) {
    throw InputError("--vary " + vary.key + ": scene " + recipe->name + " has no parameter \"" +
                     vary.key + "\" (chainbench list shows them)");
  }
  const double v = vary.values[k];
  if (v < p->min || v > p->max || (p->integer && v != std::floor(v))) {
    throw InputError("--vary " + vary.key + "=" + vary.texts[k] + ": scene " + recipe->name +
                     " takes " + (p->integer ? "whole numbers" : "values") + " in [" +
                     exact_number(p->min) + ", " + exact_number(p->max) + "]");
  }
  std::vector<std::string> with = sets;
  with.push_back(vary.key + "=" + exact_number(vary.values[k]));
  if (keeps_simulated_time(vary, sets)) {
    const double steps = std::round(recipe->steps * (1.0 / 60.0) / v);
    if (steps > limits::kMaxSteps) {
      throw InputError("--vary dt=" + vary.texts[k] + ": scene " + recipe->name +
                       " would need more than " + std::to_string(limits::kMaxSteps) +
                       " steps to last its default time");
    }
    with.push_back("steps=" + exact_number(std::max(1.0, steps)));
  }
  return make_scene(name, with);
}

}  // namespace chainbench
