// SPDX-License-Identifier: MIT
// A plugin's table (chainbench/engine_plugin.h) checked field by field before chainbench uses any
// of it: its ABI and size, name, functions, capabilities, counters and declared keys, every string
// read within its bound (plugin_text.h). A bad table is an InputError naming the plugin, the field
// and the reason.
#pragma once

#include "engines/engine.h"
#include "engines/registry.h"

#include <chainbench/engine_plugin.h>

#include <string>
#include <vector>

namespace chainbench {

// A loaded library. Never unloaded: its function pointers must outlive every world made from it.
struct Plugin {
  std::string path;
  std::string name;
  const cb_engine* api = nullptr;
  std::vector<CounterDef> counters;
  std::vector<KeyDef> keys;  // as the spec parser checks them (KeyDef)
  // Set for a library that crashed, exited or hung while its probe loaded it, when such a library
  // is kept (keep_plugins_that_fail_to_load): why. Its table is then a stand-in (no keys or
  // counters, every capability) and it is never loaded in this process.
  std::string load_failure;
};

// "plugin NAME (PATH)", as messages name a plugin.
std::string describe(const Plugin& p);

// `api` checked; `path` names it in messages. Throws InputError for anything the contract does not
// allow.
Plugin check_table(const cb_engine* api, const std::string& path);

}  // namespace chainbench
