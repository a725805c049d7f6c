// SPDX-License-Identifier: MIT
// Strings and figures a plugin hands back, checked before chainbench keeps or prints any of them.
// A plugin's memory is not chainbench's: a string is read within a bound (never past it, so an
// unterminated one is a refusal, not an overread), and only printable ASCII is echoed, cut short,
// so that a plugin can neither flood a message nor drive the terminal.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace chainbench {

// A C string read within `bound` bytes: `problem` is empty when it is terminated within the
// bound and printable ASCII (0x20-0x7e) throughout; otherwise it says why not. `shown` is what may
// be echoed: the printable part before the first fault, at most 60 characters, with what was cut.
struct PluginText {
  std::string text;     // the string when problem is empty
  std::string problem;  // e.g. "has no terminator within 64 bytes"
  std::string shown;    // e.g. "\"abc\"" or "\"abcdef...\" (cut)"
};
PluginText read_plugin_text(const char* s, std::size_t bound);

// Empty when `name` can be a counter's name: [a-z0-9_], 1-31 characters, and not a key the
// stress JSON keeps for the chain solver's own counters (budget_hits, crush_events).
std::string counter_name_problem(const std::string& name);

// Empty when `name` can be a plugin key's name: [a-z0-9_], 1-31 characters, and not "path"
// (the key that names the library).
std::string key_name_problem(const std::string& name);

// The capability bits this chainbench knows (CB_CAN_*).
std::uint32_t known_capabilities();

}  // namespace chainbench
