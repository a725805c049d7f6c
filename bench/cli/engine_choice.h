// Which engines a command runs: the list the user gave, every one of which must be able to run
// every scene (else InputError, before anything runs), or, with no list, every registered engine's
// defaults that can, with a note for each one left out.
#pragma once

#include "engine_spec.h"
#include "scene.h"

#include <string>
#include <utility>
#include <vector>

namespace chainbench {

struct EngineChoice {
  std::vector<EngineSpec> engines;
  std::vector<std::string> notes;  // "chain:variant=seed2014 left out: it has no friction, ..."
  // The defaults left out and why ("scene s: it has no friction, ..."), in registry order.
  std::vector<std::pair<EngineSpec, std::string>> left_out;
};

// `list`: "--engines" as typed, or empty for the defaults.
EngineChoice choose_engines(const std::string& list, const std::vector<const Scene*>& scenes);

// The default engine list as `--help` shows it.
std::string default_engine_list();

}  // namespace chainbench
