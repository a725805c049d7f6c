#include "engine_choice.h"

#include "input_error.h"
#include "registry.h"

namespace chainbench {

EngineChoice choose_engines(const std::string& list, const std::vector<const Scene*>& scenes) {
  EngineChoice choice;
  const bool given = !list.empty();
  for (EngineSpec& spec : given ? parse_engine_list(list) : default_engines()) {
    std::string why;
    for (const Scene* scene : scenes) {
      if (why.empty()) why = missing_capability(spec, *scene);
      if (!why.empty()) why = "scene " + scene->name + ": " + why;
      if (!why.empty()) break;
    }
    if (why.empty()) {
      choice.engines.push_back(std::move(spec));
    } else if (given) {
      throw InputError(why + " (--engines " + list + ")");
    } else {
      choice.notes.push_back(spec.label() + " left out: " + why);
      choice.left_out.emplace_back(std::move(spec), std::move(why));
    }
  }
  if (choice.engines.empty()) throw InputError("no default engine can run this scene");
  return choice;
}

std::string default_engine_list() {
  std::string s;
  for (const EngineSpec& spec : default_engines()) {
    if (!s.empty()) s += ',';
    s += spec.label();
  }
  return s;
}

}  // namespace chainbench
