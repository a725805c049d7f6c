// SPDX-License-Identifier: MIT
#include "engines/engine_spec.h"
#include "support/number_text.h"

#include "engines/registry.h"
#include "support/input_error.h"

#include <algorithm>
#include <charconv>
#include <filesystem>
#include <map>
#include <set>
#include <stdexcept>

namespace chainbench {
namespace {

std::vector<std::string> split(std::string_view text, std::string_view separators) {
  std::vector<std::string> out;
  std::string cur;
  for (const char ch : text) {
    if (separators.find(ch) != std::string_view::npos) {
      out.push_back(cur);
      cur.clear();
    } else {
      cur += ch;
    }
  }
  out.push_back(cur);
  return out;
}

std::string join(const std::vector<std::string>& items, const char* separator) {
  std::string s;
  for (const std::string& item : items)
    s += (s.empty() ? "" : separator) + item;
  return s;
}

// The default of `key` given the values of the keys before it.
std::string default_of(const KeyDef& key,
                       const std::vector<std::pair<std::string, std::string>>& settings) {
  if (key.depends_on.empty()) return key.default_value;
  for (const auto& [name, value] : settings) {
    if (name != key.depends_on) continue;
    for (const auto& [when, then] : key.default_when) {
      if (value == when) return then;
    }
  }
  return key.default_value;
}

// Every key of `spec`'s engine: its own, then those that follow from them.
std::vector<KeyDef> all_keys(const EngineDef& def, const EngineSpec& spec) {
  std::vector<KeyDef> keys = def.keys;
  if (def.more_keys) {
    std::vector<KeyDef> more = def.more_keys(spec);
    keys.insert(keys.end(), more.begin(), more.end());
  }
  return keys;
}

std::string key_names(const std::vector<KeyDef>& keys) {
  std::string s;
  for (const KeyDef& k : keys)
    s += (s.empty() ? "" : ", ") + k.name;
  return s;
}

}  // namespace

std::string checked_key_value(const std::string& what, const KeyDef& key,
                              const std::string& value) {
  if (key.file) {
    if (value.empty()) throw InputError(what + " is empty");
    std::error_code ec;
    if (!std::filesystem::is_regular_file(value, ec)) {
      throw InputError(
          what + ": " +
          (std::filesystem::exists(value, ec) ? "not a regular file: " : "no such file: ") +
          cut_for_message(value));
    }
    const std::filesystem::path absolute = std::filesystem::absolute(value, ec);
    return ec ? value : absolute.lexically_normal().string();
  }
  if (key.text) {
    if (value.empty()) throw InputError(what + " is empty");
    return value;
  }
  if (!key.choices.empty()) {
    if (std::find(key.choices.begin(), key.choices.end(), value) == key.choices.end()) {
      throw InputError(what + " must be one of " + join(key.choices, "|") + ", got \"" +
                       cut_for_message(value) + "\"");
    }
    return value;
  }
  if (key.integer) {
    return std::to_string(parse_integer(what, value, static_cast<long long>(key.min),
                                        static_cast<long long>(key.max)));
  }
  const double v = parse_number(what, value);
  if (v < key.min || v > key.max) {
    throw InputError(what + ": " + cut_for_message(value) + " is out of range [" +
                     exact_number(key.min) + ", " + exact_number(key.max) + "]");
  }
  return exact_number(v + 0.0);  // -0 is 0: one spec, one label
}

void add_key_settings(const std::string& where, const std::vector<KeyDef>& keys,
                      const std::vector<std::pair<std::string, std::string>>& given,
                      EngineSpec& spec) {
  for (const auto& g : given) {
    const std::string& key = g.first;  // named: clang before 16 cannot capture a binding
    if (std::none_of(keys.begin(), keys.end(), [&](const KeyDef& k) { return k.name == key; })) {
      throw InputError(where + ": unknown key \"" + cut_for_message(key) + "\" for " + spec.engine +
                       " (keys: " + key_names(keys) + ")");
    }
  }
  for (const KeyDef& k : keys) {
    const auto g =
        std::find_if(given.begin(), given.end(), [&](const auto& p) { return p.first == k.name; });
    if (g != given.end()) {
      spec.settings.emplace_back(k.name, checked_key_value(where + ": " + k.name, k, g->second));
    } else if (std::string d = default_of(k, spec.settings); !d.empty()) {
      spec.settings.emplace_back(k.name, std::move(d));
    } else {
      throw InputError(where + ": " + spec.engine + " needs " + k.name + "= (" + k.help + ")");
    }
  }
}

const std::string& EngineSpec::get(std::string_view key) const {
  for (const auto& [k, v] : settings) {
    if (k == key) return v;
  }
  throw std::logic_error("engine spec " + str() + " has no key " + std::string(key));
}

long long EngineSpec::get_int(std::string_view key) const {
  return std::stoll(get(key));
}

double EngineSpec::get_number(std::string_view key) const {
  return std::stod(get(key));
}

std::string EngineSpec::str() const {
  std::string s = engine;
  for (std::size_t i = 0; i < settings.size(); ++i)
    s += (i == 0 ? ":" : ",") + settings[i].first + "=" + settings[i].second;
  return s;
}

std::string EngineSpec::label() const {
  const EngineDef& def = engine_def(engine);
  const std::vector<KeyDef> keys = all_keys(def, *this);
  std::string s = engine;
  bool first = true;
  for (const auto& setting : settings) {
    // Named copies of the pair's halves: clang before 16 cannot capture a structured binding.
    const std::string& key = setting.first;
    const std::string& value = setting.second;
    const auto declared =
        std::find_if(keys.begin(), keys.end(), [&](const KeyDef& k) { return k.name == key; });
    // A key is shown when it differs from its default here, a file by its name alone.
    if (declared != keys.end() && value == default_of(*declared, settings)) continue;
    const bool file = declared != keys.end() && declared->file;
    s += (first ? ":" : ",") + key + "=" +
         (file ? std::filesystem::path(value).filename().string() : value);
    first = false;
  }
  return s;
}

EngineSpec parse_engine_spec(std::string_view text) {
  const std::string where = "engine spec \"" + cut_for_message(std::string(text)) + "\"";
  // Specs reach the terminal, the plugin and JSON outputs: UTF-8 text only.
  if (const std::string problem = text_problem(std::string(text)); !problem.empty())
    throw InputError(where + ": " + problem);
  const std::size_t colon = text.find(':');
  const std::string name(text.substr(0, colon));
  const auto& registry = engine_registry();
  const auto def = std::find_if(registry.begin(), registry.end(),
                                [&](const EngineDef& e) { return e.name == name; });
  if (def == registry.end()) {
    std::vector<std::string> known;
    for (const EngineDef& e : registry)
      known.push_back(e.name);
    throw InputError(where + ": unknown engine \"" + cut_for_message(name) +
                     "\" (known: " + join(known, ", ") + ")");
  }
  // Keys the engine declares, and the others, which may follow from them (more_keys).
  std::vector<std::pair<std::string, std::string>> given, rest;
  if (colon != std::string_view::npos) {
    for (const std::string& kv : split(text.substr(colon + 1), ",")) {
      const std::size_t eq = kv.find('=');
      if (eq == std::string::npos || eq == 0) {
        throw InputError(where + ": \"" + cut_for_message(kv) + "\" is not key=value");
      }
      const std::string key = kv.substr(0, eq), value = kv.substr(eq + 1);
      auto seen = [&](const auto& list) {
        return std::any_of(list.begin(), list.end(), [&](const auto& g) { return g.first == key; });
      };
      if (seen(given) || seen(rest))
        throw InputError(where + ": key \"" + cut_for_message(key) + "\" given twice");
      const bool declared = std::any_of(def->keys.begin(), def->keys.end(),
                                        [&](const KeyDef& k) { return k.name == key; });
      (declared ? given : rest).emplace_back(key, value);
    }
  }
  EngineSpec spec{name, {}};
  if (!def->more_keys && !rest.empty()) given.push_back(rest.front());  // refused as unknown
  add_key_settings(where, def->keys, given, spec);
  if (def->more_keys) add_key_settings(where, def->more_keys(spec), rest, spec);
  return spec;
}

std::vector<EngineSpec> parse_grid(std::string_view text) {
  const std::string where = "--grid \"" + cut_for_message(std::string(text)) + "\"";
  const std::size_t colon = text.find(':');
  const std::string engine(text.substr(0, colon));
  std::vector<std::pair<std::string, std::vector<std::string>>> axes;
  if (colon != std::string_view::npos) {
    for (const std::string& part : split(text.substr(colon + 1), ";")) {
      const std::size_t eq = part.find('=');
      if (eq == std::string::npos || eq == 0 || eq + 1 == part.size()) {
        throw InputError(where + ": \"" + cut_for_message(part) + "\" is not key=value,value,...");
      }
      axes.emplace_back(part.substr(0, eq), split(part.substr(eq + 1), ","));
    }
  }
  std::size_t total = 1;
  for (const auto& [key, values] : axes) {
    total *= values.size();
    if (total > 10'000) throw InputError(where + ": more than 10,000 combinations");
  }
  std::vector<EngineSpec> out;
  for (std::size_t k = 0; k < total; ++k) {
    std::string spec = engine;
    std::size_t rest = k;
    for (std::size_t a = 0; a < axes.size(); ++a) {
      const auto& [key, values] = axes[a];
      spec += (a == 0 ? ":" : ",") + key + "=" + values[rest % values.size()];
      rest /= values.size();
    }
    out.push_back(parse_engine_spec(spec));  // validates keys and values
  }
  return out;
}

std::vector<EngineSpec> parse_engine_list(std::string_view text) {
  std::vector<std::string> specs;
  for (const std::string& token : split(text, ",;")) {
    if (token.empty()) {
      throw InputError("engine list \"" + cut_for_message(std::string(text)) + "\": empty entry");
    }
    const bool continues =
        token.find('=') != std::string::npos && token.find(':') == std::string::npos;
    if (continues && !specs.empty()) {
      specs.back() += (specs.back().find(':') == std::string::npos ? ":" : ",") + token;
    } else {
      specs.push_back(token);
    }
  }
  if (specs.empty()) {
    throw InputError("engine list \"" + cut_for_message(std::string(text)) + "\": no engine");
  }
  std::vector<EngineSpec> out;
  // Rows, `met by` and --require name engines by label: two engines must not share one. Looked
  // up in maps, so that a list of n specs is checked in n log n.
  std::map<std::string, std::string> str_of_label;
  std::set<std::string> strs;
  const std::string where = "engine list \"" + cut_for_message(std::string(text)) + "\"";
  for (const std::string& s : specs) {
    EngineSpec spec = parse_engine_spec(s);
    const std::string str = spec.str(), label = spec.label();
    if (!strs.insert(str).second) throw InputError(where + ": " + label + " given twice");
    const auto [earlier, fresh] = str_of_label.emplace(label, str);
    if (!fresh) {
      throw InputError(where + ": " + earlier->second + " and " + str + " would both be labelled " +
                       label + " (give the files different names)");
    }
    out.push_back(std::move(spec));
  }
  return out;
}

}  // namespace chainbench
