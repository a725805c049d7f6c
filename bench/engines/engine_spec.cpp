#include "engine_spec.h"

#include "input_error.h"

#include <algorithm>
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

std::string join_choices(const std::vector<std::string>& choices) {
  std::string s;
  for (const auto& c : choices)
    s += (s.empty() ? "" : "|") + c;
  return s;
}

}  // namespace

const std::vector<EngineInfo>& engine_catalog() {
  static const std::vector<EngineInfo> catalog = {
      {"chain",
       "the collision-chaining solver of solver/ (no friction, no rotation)",
       {{"variant",
         "modern",
         {"modern", "seed2014"},
         0,
         0,
         "modern: chaining done right; seed2014: the 2014 engine, quirks included"},
        {"velocity",
         "",
         {"zero", "inelastic"},
         0,
         0,
         "velocity after a push; default inelastic, zero for variant=seed2014"},
        {"passes", "4", {}, 1, 1000, "modern: contact sweeps per step, at most"},
        {"budget", "64", {}, 1, 1000000, "pair resolutions per body per step (+1024)"},
        {"depth", "2048", {}, 1, 16384, "seed2014: recursion depth limit"}}},
      {"box2d",
       "Box2D 2.4.1 (Debian libbox2d), fixed rotation unless the scene rotates, CCD and sleep off",
       {{"vel_iters", "8", {}, 1, 1000, "velocity iterations"},
        {"pos_iters", "3", {}, 0, 1000, "position iterations"},
        {"substeps", "1", {}, 1, 1000, "world steps per scene step"},
        {"skin",
         "compensate",
         {"compensate", "raw"},
         0,
         0,
         "compensate: polygons built 7.5 mm smaller per side so boxes rest at their faces"},
        {"warm", "1", {}, 0, 1, "warm starting"}}},
  };
  return catalog;
}

const std::string& EngineSpec::get(std::string_view key) const {
  for (const auto& [k, v] : settings) {
    if (k == key) return v;
  }
  throw std::logic_error("engine spec has no key " + std::string(key));
}

long long EngineSpec::get_int(std::string_view key) const {
  return std::stoll(get(key));
}

std::string EngineSpec::str() const {
  std::string s = engine;
  for (std::size_t i = 0; i < settings.size(); ++i) {
    s += (i == 0 ? ":" : ",") + settings[i].first + "=" + settings[i].second;
  }
  return s;
}

std::string EngineSpec::short_str() const {
  // A default can depend on the variant (each chain variant has its own velocity rule), so keys
  // after the variant are compared with that variant's defaults: the short form must parse back to
  // this very spec.
  const EngineSpec defaults = parse_engine_spec(engine);
  const EngineSpec variant_defaults =
      engine == "chain" ? parse_engine_spec("chain:variant=" + get("variant")) : defaults;
  std::string s = engine;
  bool first = true;
  for (std::size_t i = 0; i < settings.size(); ++i) {
    const EngineSpec& d = settings[i].first == "variant" ? defaults : variant_defaults;
    if (settings[i].second == d.settings[i].second) continue;
    s += (first ? ":" : ",") + settings[i].first + "=" + settings[i].second;
    first = false;
  }
  return s;
}

EngineSpec parse_engine_spec(std::string_view text) {
  const std::string where = "engine spec \"" + std::string(text) + "\"";
  const std::size_t colon = text.find(':');
  const std::string name(text.substr(0, colon));
  const auto& catalog = engine_catalog();
  const auto info = std::find_if(catalog.begin(), catalog.end(),
                                 [&](const EngineInfo& e) { return e.name == name; });
  if (info == catalog.end()) {
    throw InputError(where + ": unknown engine \"" + name + "\" (known: chain, box2d)");
  }
  std::vector<std::pair<std::string, std::string>> given;
  if (colon != std::string_view::npos) {
    for (const std::string& kv : split(text.substr(colon + 1), ",")) {
      const std::size_t eq = kv.find('=');
      if (eq == std::string::npos || eq == 0) {
        throw InputError(where + ": \"" + kv + "\" is not key=value");
      }
      const std::string key = kv.substr(0, eq);
      const auto known = std::find_if(info->keys.begin(), info->keys.end(),
                                      [&](const EngineKey& k) { return k.name == key; });
      if (known == info->keys.end()) {
        std::string keys;
        for (const auto& k : info->keys)
          keys += (keys.empty() ? "" : ", ") + k.name;
        throw InputError(where + ": unknown key \"" + key + "\" for " + name + " (keys: " + keys +
                         ")");
      }
      if (std::any_of(given.begin(), given.end(), [&](const auto& g) { return g.first == key; })) {
        throw InputError(where + ": key \"" + key + "\" given twice");
      }
      std::string value = kv.substr(eq + 1);
      if (known->choices.empty()) {
        value = std::to_string(parse_integer(where + ": " + key, value, known->min, known->max));
      } else if (std::find(known->choices.begin(), known->choices.end(), value) ==
                 known->choices.end()) {
        throw InputError(where + ": " + key + " must be one of " + join_choices(known->choices) +
                         ", got \"" + value + "\"");
      }
      given.emplace_back(key, value);
    }
  }
  EngineSpec spec{name, {}};
  for (const EngineKey& k : info->keys) {
    const auto g =
        std::find_if(given.begin(), given.end(), [&](const auto& p) { return p.first == k.name; });
    spec.settings.emplace_back(k.name, g != given.end() ? g->second : k.default_value);
  }
  if (name == "chain") {  // the velocity rule defaults by variant: each variant's own rule
    for (auto& [k, v] : spec.settings) {
      if (k == "velocity" && v.empty())
        v = spec.get("variant") == "seed2014" ? "zero" : "inelastic";
    }
  }
  return spec;
}

std::vector<EngineSpec> parse_engine_list(std::string_view text) {
  std::vector<std::string> specs;
  for (const std::string& token : split(text, ",;")) {
    if (token.empty()) throw InputError("engine list \"" + std::string(text) + "\": empty entry");
    const bool continues =
        token.find('=') != std::string::npos && token.find(':') == std::string::npos;
    if (continues && !specs.empty()) {
      specs.back() += (specs.back().find(':') == std::string::npos ? ":" : ",") + token;
    } else {
      specs.push_back(token);
    }
  }
  std::vector<EngineSpec> out;
  for (const std::string& s : specs)
    out.push_back(parse_engine_spec(s));
  return out;
}

}  // namespace chainbench
