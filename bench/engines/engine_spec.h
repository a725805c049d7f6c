// Engine specs: "NAME[:key=value,key=value...]", e.g. "chain:variant=seed2014" or
// "box2d:vel_iters=4,substeps=2". A parsed spec holds every key of its engine, defaults filled
// in, so its canonical string names exactly what ran.
#pragma once

#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace chainbench {

struct EngineKey {
  std::string name;
  std::string default_value;
  std::vector<std::string> choices;  // empty: a whole number in [min, max]
  long long min = 0;
  long long max = 0;
  std::string help;
};

struct EngineInfo {
  std::string name;
  std::string description;
  std::vector<EngineKey> keys;
};

// The engines chainbench can run, with their keys in canonical order.
const std::vector<EngineInfo>& engine_catalog();

struct EngineSpec {
  std::string engine;
  std::vector<std::pair<std::string, std::string>> settings;  // every key, canonical order

  const std::string& get(std::string_view key) const;
  long long get_int(std::string_view key) const;
  std::string str() const;  // canonical: "chain:variant=modern,velocity=inelastic,..."
  // Only the keys that differ from the engine's defaults: "chain:variant=seed2014", "box2d".
  std::string short_str() const;
};

// Throws InputError naming the spec and the unknown engine, key or bad value.
EngineSpec parse_engine_spec(std::string_view text);
// A list of specs separated by ',' or ';': "chain,chain:variant=seed2014,velocity=zero,box2d".
// A token with '=' and no ':' continues the spec before it.
std::vector<EngineSpec> parse_engine_list(std::string_view text);

}  // namespace chainbench
