// SPDX-License-Identifier: MIT
// Engine specs: "NAME[:key=value,key=value...]", e.g. "chain:variant=seed2014" or
// "chain:velocity=zero,max_passes=8". A parsed spec holds every key its engine declares
// (registry.h), defaults filled in, so its canonical string names exactly what ran; a spec travels
// with its run.
#pragma once

#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace chainbench {

struct EngineSpec {
  std::string engine;
  // Every declared key in the engine's order, then those that follow from them (a plugin's).
  std::vector<std::pair<std::string, std::string>> settings;

  const std::string& get(std::string_view key) const;  // std::logic_error for an unknown key
  long long get_int(std::string_view key) const;
  double get_number(std::string_view key) const;
  // Canonical: "chain:variant=modern,velocity=inelastic,...".
  std::string str() const;
  // The keys that differ from their defaults, as tables print it: "chain:variant=seed2014",
  // "chain". Parses back to this very spec, except that a file key shows the file's name only.
  std::string label() const;

  friend bool operator==(const EngineSpec&, const EngineSpec&) = default;
};

struct KeyDef;

// `value` as the canonical string has it, or InputError "WHAT: reason" (`what` names the value:
// the spec and the key, "chain:passes", or a plugin's key's default).
std::string checked_key_value(const std::string& what, const KeyDef& key, const std::string& value);
// Appends to spec.settings every key of `keys` in order: its value in `given` (checked) or its
// default. InputError naming `where` for a key of `given` that `keys` lacks, a bad value or a
// missing required key.
void add_key_settings(const std::string& where, const std::vector<KeyDef>& keys,
                      const std::vector<std::pair<std::string, std::string>>& given,
                      EngineSpec& spec);

// Throws InputError naming the spec and the unknown engine, key or bad value.
EngineSpec parse_engine_spec(std::string_view text);
// "NAME:key=v1,v2;key=v3,v4": every combination of the listed values, the other keys at their
// defaults. Throws InputError for unknown engines, keys or values, or more than 10,000 specs.
std::vector<EngineSpec> parse_grid(std::string_view text);
// A list of specs separated by ',' or ';': "chain,chain:variant=seed2014,velocity=zero,NAME".
// A token with '=' and no ':' continues the spec before it.
std::vector<EngineSpec> parse_engine_list(std::string_view text);

}  // namespace chainbench
