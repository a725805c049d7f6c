// SPDX-License-Identifier: MIT
// The plugin engine (`plugin:path=FILE`) over a table already in memory: what a loaded library's
// chainbench_engine_plugin() returns, checked and used exactly as for a library. The plugin fuzz
// target (tests/fuzz/plugin_fuzz.cpp) drives it with a fake plugin whose every return comes from
// the fuzzer.
#pragma once

#include "engines/engine.h"
#include "engines/engine_spec.h"

#include <chainbench/engine_plugin.h>

#include <memory>
#include <string>

namespace chainbench {

// An engine stepping the plugin world `table` builds for `scene`; `label` stands for the
// library's path in messages, and spec's keys other than `path` reach the plugin as settings.
// Throws InputError for a table, a return or a state the plugin contract does not allow, here
// or from the engine's step, read_state and counters; `table` must outlive the engine.
std::unique_ptr<Engine> make_plugin_engine(const cb_engine* table, const std::string& label,
                                           const EngineSpec& spec, const Scene& scene);

}  // namespace chainbench
