// SPDX-License-Identifier: MIT
// Which engines a command runs: the list the user gave, every one of which must be able to run
// every scene (else InputError, before anything runs), or, with no list or with the entry
// `defaults`, every registered engine's defaults that can, with a note for each one left out.
#pragma once

#include "engines/engine_spec.h"
#include "model/scene.h"
#include "support/output_file.h"

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

// The entry of an engine list that stands for the defaults: "defaults,box2d:sleep=1" runs them
// and one more.
inline constexpr const char* kDefaultEngines = "defaults";

// `list`: "--engines" as typed, or empty for the defaults. An entry `defaults` adds the defaults
// that can run every scene (the others left out with a note, as with no list).
EngineChoice choose_engines(const std::string& list, const std::vector<const Scene*>& scenes);

// The default engine list as `--help` shows it.
std::string default_engine_list();

// InputError (exit 2) if an output names a file one of `specs` reads (a plugin's library, by
// device and inode as refuse_clashing_files compares): writing it would replace what runs.
void refuse_outputs_over_engine_files(const std::vector<EngineSpec>& specs,
                                      const std::vector<NamedFile>& outputs);

}  // namespace chainbench
