// SPDX-License-Identifier: MIT
#include "cli/engine_choice.h"

#include "engines/registry.h"
#include "support/input_error.h"

#include <algorithm>
#include <utility>

namespace chainbench {

namespace {

// The list with its entries `defaults` taken out, and whether there was one. An entry is what
// lies between ',' or ';'; a key=value entry continues the spec before it, so none may follow
// `defaults`.
std::pair<std::string, bool> take_defaults(const std::string& list) {
  if (list.empty()) return {list, false};
  std::string rest;
  bool defaults = false, after_defaults = false, first = true;
  std::size_t begin = 0;
  while (begin <= list.size()) {
    const std::size_t end = std::min(list.find_first_of(",;", begin), list.size());
    const std::string entry = list.substr(begin, end - begin);
    if (entry.empty()) throw InputError("engine list \"" + list + "\": empty entry");
    if (entry == kDefaultEngines) {
      if (defaults) throw InputError("--engines " + list + ": " + kDefaultEngines + " given twice");
      defaults = after_defaults = true;
    } else {
      if (after_defaults && entry.find('=') != std::string::npos &&
          entry.find(':') == std::string::npos) {
        throw InputError("--engines " + list + ": \"" + entry + "\" follows " + kDefaultEngines +
                         ", which takes no keys");
      }
      after_defaults = false;
      // ',' and ';' separate alike; an empty entry is kept, for the list's parser to refuse.
      rest += (first ? "" : ",") + entry;
      first = false;
    }
    begin = end + 1;
  }
  return {rest, defaults};
}

}  // namespace

EngineChoice choose_engines(const std::string& list, const std::vector<const Scene*>& scenes) {
  EngineChoice choice;
  const auto [named, defaults] = take_defaults(list);
  std::vector<EngineSpec> specs;
  std::vector<bool> given;  // per spec: named in the list (else one of the defaults)
  if (list.empty() || defaults) {
    for (EngineSpec& spec : default_engines()) {
      specs.push_back(std::move(spec));
      given.push_back(false);
    }
  }
  if (!named.empty()) {
    for (EngineSpec& spec : parse_engine_list(named)) {
      // A default named again is run once, as the one the user named.
      for (std::size_t k = 0; k < specs.size(); ++k) {
        if (!given[k] && specs[k] == spec) {
          specs.erase(specs.begin() + static_cast<std::ptrdiff_t>(k));
          given.erase(given.begin() + static_cast<std::ptrdiff_t>(k));
          break;
        }
      }
      specs.push_back(std::move(spec));
      given.push_back(true);
    }
  }
  for (std::size_t k = 0; k < specs.size(); ++k) {
    std::string why;
    for (const Scene* scene : scenes) {
      if (why.empty()) why = missing_capability(specs[k], *scene);
      if (!why.empty()) why = "scene " + scene->name + ": " + why;
      if (!why.empty()) break;
    }
    if (why.empty()) {
      choice.engines.push_back(std::move(specs[k]));
    } else if (given[k]) {
      throw InputError(why + " (--engines " + list + ")");
    } else {
      choice.notes.push_back(specs[k].label() + " left out: " + why);
      choice.left_out.emplace_back(std::move(specs[k]), std::move(why));
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

void refuse_outputs_over_engine_files(const std::vector<EngineSpec>& specs,
                                      const std::vector<NamedFile>& outputs) {
  std::vector<std::string> files;
  for (const EngineSpec& spec : specs) {
    for (const EngineDef& def : engine_registry()) {
      if (def.name != spec.engine) continue;
      for (const KeyDef& key : def.keys) {
        if (key.file) files.push_back(spec.get(key.name));
      }
    }
  }
  std::vector<NamedFile> inputs;
  for (const std::string& file : files)  // filled first: inputs point into it
    inputs.emplace_back("--engines", &file);
  refuse_clashing_files(outputs, inputs);
}

}  // namespace chainbench
