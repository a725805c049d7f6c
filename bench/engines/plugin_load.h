// SPDX-License-Identifier: MIT
// How a plugin library that dies while it is loaded is met (bench/engines/plugin_engine.cpp loads
// every library in a child process first): refused by path, or kept for `stress`.
#pragma once

#include <string>
#include <vector>

namespace chainbench {

// Whether a library that crashes, exits or hangs while it is loaded (in a child process first)
// stops the command (InputError, the default) or is kept, for `stress`, as a plugin that is
// loaded again only in each case's child process, so that each of its cases is a crash row and
// the rest of the matrix goes on. Set before any plugin spec is read.
void keep_plugins_that_fail_to_load(bool keep);

// Every library kept so: "plugin PATH: crashed while loading: signal 11 (SIGSEGV)".
std::vector<std::string> plugins_that_failed_to_load();

}  // namespace chainbench
