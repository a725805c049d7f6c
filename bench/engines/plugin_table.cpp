// SPDX-License-Identifier: MIT
#include "engines/plugin_table.h"
#include "support/number_text.h"

#include "engines/engine_spec.h"
#include "engines/plugin_text.h"
#include "support/input_error.h"
#include "support/text_table.h"

#include <cmath>
#include <set>

namespace chainbench {
namespace {

constexpr std::size_t kMaxCounters = 16;
constexpr std::size_t kNameBound = 64;     // a plugin's name: under 64 bytes, terminated
constexpr std::size_t kCounterBound = 32;  // a counter's name: under 32 bytes, terminated
constexpr std::size_t kMaxKeys = 32;
constexpr std::size_t kKeyBound = 32;               // a key's name, as a counter's
constexpr std::size_t kDefaultBound = 64;           // a key's default
constexpr std::size_t kHelpBound = 128;             // a key's help line
constexpr double kWholeLimit = 9007199254740992.0;  // 2^53: every whole double up to it is exact

// A string of the plugin's read within `bound`, or InputError saying what of it is bad.
std::string plugin_string(const std::string& what, const char* raw, std::size_t bound) {
  const PluginText t = read_plugin_text(raw, bound);
  if (!t.problem.empty()) throw InputError(what + " " + t.problem + ": " + t.shown);
  return t.text;
}

// The plugin's declared keys as KeyDefs, each checked: its name, type, range, default and help.
std::vector<KeyDef> check_keys(const Plugin& p) {
  const cb_engine& api = *p.api;
  if (api.key_count > kMaxKeys) {
    throw InputError(describe(p) + ": declares " + std::to_string(api.key_count) +
                     " keys, more than " + std::to_string(kMaxKeys));
  }
  if (api.key_count > 0 && !api.keys) {
    throw InputError(describe(p) + ": declares " + std::to_string(api.key_count) +
                     " keys and gives no table of them");
  }
  std::vector<KeyDef> keys;
  for (std::uint32_t k = 0; k < api.key_count; ++k) {
    const cb_key& raw = api.keys[k];
    const std::string at = describe(p) + ": key " + std::to_string(k);
    const PluginText name = read_plugin_text(raw.name, kKeyBound);
    const std::string problem = name.problem.empty() ? key_name_problem(name.text) : name.problem;
    if (!problem.empty()) {
      throw InputError(at + " has no valid name (letters a-z, digits and _, under 32): its name " +
                       problem + ": " + name.shown);
    }
    const std::string key_at = describe(p) + ": key " + name.text;
    for (const KeyDef& earlier : keys) {
      if (earlier.name == name.text) {
        throw InputError(at + " is named " + name.text +
                         ", as an earlier key is: each key needs a name of its own");
      }
    }
    KeyDef def;
    def.name = name.text;
    def.help = plugin_string(key_at + ": its help", raw.help, kHelpBound);
    if (raw.type == CB_KEY_TEXT) {
      def.text = true;
    } else if (raw.type == CB_KEY_NUMBER || raw.type == CB_KEY_INTEGER) {
      def.integer = raw.type == CB_KEY_INTEGER;
      def.min = raw.min, def.max = raw.max;
      const double limit = def.integer ? kWholeLimit : HUGE_VAL;
      auto bad = [&](double v) {
        return !std::isfinite(v) || std::abs(v) > limit || (def.integer && v != std::floor(v));
      };
      if (bad(def.min) || bad(def.max) || def.min > def.max) {
        throw InputError(key_at + ": its range [" + exact_number(def.min) + ", " +
                         exact_number(def.max) + "] is not " +
                         (def.integer ? "two whole numbers within 2^53" : "two finite numbers") +
                         ", the first no larger");
      }
    } else {
      throw InputError(key_at + ": its type is " + std::to_string(raw.type) +
                       " (CB_KEY_NUMBER 0, CB_KEY_INTEGER 1 or CB_KEY_TEXT 2)");
    }
    const std::string value =
        plugin_string(key_at + ": its default", raw.default_value, kDefaultBound);
    // The spec parser's own check: a default is a value the key accepts.
    def.default_value = checked_key_value(key_at + ": its default", def, value);
    keys.push_back(std::move(def));
  }
  return keys;
}

}  // namespace

Plugin check_table(const cb_engine* api, const std::string& path) {
  const std::string where = "plugin " + path;
  Plugin p;
  p.path = path;
  p.api = api;
  if (p.api->abi != CHAINBENCH_PLUGIN_ABI) {
    throw InputError(where + ": built for plugin ABI " + std::to_string(p.api->abi) +
                     ", this chainbench loads ABI " + std::to_string(CHAINBENCH_PLUGIN_ABI) +
                     ": rebuild it against this chainbench's engine_plugin.h");
  }
  if (p.api->size != sizeof(cb_engine)) {
    throw InputError(where + ": its cb_engine is " + std::to_string(p.api->size) +
                     " bytes, this chainbench's is " + std::to_string(sizeof(cb_engine)));
  }
  if (p.api->name) {
    const PluginText name = read_plugin_text(p.api->name, kNameBound);
    if (!name.problem.empty()) {
      throw InputError(where + ": its name " + name.problem +
                       " (a name is printable ASCII, under " + std::to_string(kNameBound) +
                       " bytes): " + name.shown);
    }
    p.name = name.text;
  }
  if (p.name.empty()) p.name = "(unnamed)";
  if (!p.api->create || !p.api->set_velocity || !p.api->step || !p.api->read_state ||
      !p.api->destroy || (p.api->counter_count > 0 && !p.api->read_counters)) {
    throw InputError(describe(p) + ": its cb_engine leaves a required function null");
  }
  if (p.api->counter_count > kMaxCounters) {
    throw InputError(describe(p) + ": reports " + std::to_string(p.api->counter_count) +
                     " counters, more than " + std::to_string(kMaxCounters));
  }
  if ((p.api->capabilities & CB_CAN_LIFETIMES) && (!p.api->add_body || !p.api->remove_body)) {
    throw InputError(describe(p) + ": sets CB_CAN_LIFETIMES and leaves " +
                     (p.api->add_body ? "remove_body" : "add_body") + " null");
  }
  if (const std::uint32_t unknown = p.api->capabilities & ~known_capabilities()) {
    throw InputError(describe(p) + ": sets capability bits " + std::to_string(unknown) +
                     " that this chainbench does not know (it knows CB_CAN_*, " +
                     std::to_string(known_capabilities()) + " together)");
  }
  if (p.api->counter_count > 0 && !p.api->counters) {
    throw InputError(describe(p) + ": reports " + std::to_string(p.api->counter_count) +
                     " counters and gives no table of them");
  }
  std::set<std::string> seen;
  for (std::uint32_t k = 0; k < p.api->counter_count; ++k) {
    const cb_counter& raw = p.api->counters[k];
    const PluginText name = read_plugin_text(raw.name, kCounterBound);
    const std::string problem =
        name.problem.empty() ? counter_name_problem(name.text) : name.problem;
    if (!problem.empty()) {
      throw InputError(describe(p) + ": counter " + std::to_string(k) +
                       " has no valid name (letters a-z, digits and _, under 32): its name " +
                       problem + ": " + name.shown);
    }
    if (!seen.insert(name.text).second) {
      throw InputError(describe(p) + ": counter " + std::to_string(k) + " is named " + name.text +
                       ", as an earlier counter is: each counter needs a name of its own");
    }
    const std::string at = describe(p) + ": counter " + name.text;
    CounterDef def{name.text, Aggregate::kMean,
                   plugin_string(at + ": its description", raw.description, kHelpBound), name.text};
    switch (raw.aggregate) {
      case CB_AGG_MEAN:
        def.aggregate = Aggregate::kMean;
        break;
      case CB_AGG_MAX:
        def.aggregate = Aggregate::kMax;
        break;
      case CB_AGG_SUM:
        def.aggregate = Aggregate::kSum;
        break;
      case CB_AGG_LAST:
        def.aggregate = Aggregate::kLast;
        break;
      default:
        throw InputError(at + ": its aggregate is " + std::to_string(raw.aggregate) +
                         " (CB_AGG_MEAN 0, CB_AGG_MAX 1, CB_AGG_SUM 2 or CB_AGG_LAST 3)");
    }
    p.counters.push_back(std::move(def));
  }
  p.keys = check_keys(p);
  return p;
}

std::string describe(const Plugin& p) {
  return "plugin " + p.name + " (" + p.path + ")";
}

}  // namespace chainbench
