// SPDX-License-Identifier: MIT
#include "engines/plugin_text.h"

#include <chainbench/engine_plugin.h>

#include <cstdio>
#include <cstring>

namespace chainbench {
namespace {

constexpr std::size_t kShown = 60;  // characters of a refused string that a message echoes

bool printable(unsigned char c) {
  return c >= 0x20 && c <= 0x7e;
}

std::string hex_byte(unsigned char c) {
  char buffer[8];
  std::snprintf(buffer, sizeof buffer, "0x%02x", c);
  return buffer;
}

}  // namespace

PluginText read_plugin_text(const char* s, std::size_t bound) {
  PluginText out;
  if (!s) {
    out.problem = "is null";
    out.shown = "(null)";
    return out;
  }
  const std::size_t length = strnlen(s, bound);
  std::size_t good = 0;
  while (good < length && printable(static_cast<unsigned char>(s[good])))
    ++good;
  const std::size_t kept = good < kShown ? good : kShown;
  out.shown.push_back('"');
  out.shown.append(s, kept);
  out.shown.push_back('"');
  if (good > kept || good < length) out.shown += " (cut)";
  if (length == bound) {
    out.problem = "has no terminator within " + std::to_string(bound) + " bytes";
  } else if (good < length) {
    out.problem = "holds the non-printable byte " + hex_byte(static_cast<unsigned char>(s[good])) +
                  " at offset " + std::to_string(good);
  } else {
    out.text.assign(s, length);
  }
  if (!out.problem.empty() && length > 0 && good == 0) out.shown = "(nothing printable)";
  return out;
}

namespace {

// Empty when `name` is 1-31 characters of a-z, 0-9 and _.
std::string identifier_problem(const std::string& name) {
  if (name.empty()) return "is empty";
  if (name.size() >= 32) return "is " + std::to_string(name.size()) + " characters, not under 32";
  for (const char c : name) {
    if (!((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_'))
      return "holds '" + std::string(1, c) + "' (only a-z, 0-9 and _)";
  }
  return {};
}

}  // namespace

std::string key_name_problem(const std::string& name) {
  if (std::string problem = identifier_problem(name); !problem.empty()) return problem;
  if (name == "path") return "is path, the key that names the library";
  return {};
}

std::string counter_name_problem(const std::string& name) {
  if (std::string problem = identifier_problem(name); !problem.empty()) return problem;
  // The stress JSON keeps these keys for the chain solver's counters of those names.
  for (const char* reserved : {"budget_hits", "crush_events"}) {
    if (name == reserved) return "is reserved for the chain solver's own counter";
  }
  return {};
}

std::uint32_t known_capabilities() {
  return CB_CAN_ROTATE | CB_CAN_FRICTION | CB_CAN_RESTITUTION | CB_CAN_KINEMATIC |
         CB_CAN_AXIS_DRIVES | CB_CAN_LIFETIMES;
}

}  // namespace chainbench
