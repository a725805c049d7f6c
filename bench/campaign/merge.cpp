// SPDX-License-Identifier: MIT
#include "campaign/merge.h"

#include "campaign/sweep.h"
#include "judge/verdict.h"
#include "support/input_error.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <set>

namespace chainbench {
namespace {

using nlohmann::ordered_json;

// The part's shard block, checked for its own consistency.
struct Block {
  std::string command, version, grid;
  int index = 0, count = 0;
  std::size_t units = 0;
  std::vector<std::size_t> ran;
};

// The field `key` of `j` (at `where` in the part), of the kind `is` checks; InputError naming
// the file, the field and what it should be.
const ordered_json& field(const ShardPart& p, const ordered_json& j, const std::string& where,
                          const char* key, bool (ordered_json::*is)() const noexcept,
                          const char* kind) {
  const std::string name = where.empty() ? std::string(key) : where + "." + key;
  const auto it = j.find(key);
  if (it == j.end()) throw InputError(p.file + ": " + name + ": missing (should be " + kind + ")");
  if (!((*it).*is)())
    throw InputError(p.file + ": " + name + ": should be " + kind + ", got " + it->type_name());
  return *it;
}

// The results a part holds are of the form its command writes, so that merging them cannot
// stumble on a field that is missing or of another kind.
void check_results(const ShardPart& p, const std::string& command) {
  using J = ordered_json;
  if (command == "sweep") {
    const J& scenes = field(p, p.json, "", "scenes", &J::is_array, "an array");
    for (std::size_t s = 0; s < scenes.size(); ++s) {
      const std::string at = "scenes[" + std::to_string(s) + "]";
      if (!scenes[s].is_object())
        throw InputError(p.file + ": " + at + ": should be an object, got " +
                         scenes[s].type_name());
      const J& points = field(p, scenes[s], at, "points", &J::is_array, "an array");
      for (std::size_t k = 0; k < points.size(); ++k) {
        const std::string pt = at + ".points[" + std::to_string(k) + "]";
        if (!points[k].is_object())
          throw InputError(p.file + ": " + pt + ": should be an object, got " +
                           points[k].type_name());
        field(p, points[k], pt, "engine", &J::is_string, "a string");
        field(p, points[k], pt, "ms_per_step", &J::is_number, "a number");
        const J& error =
            field(p, points[k], pt, "final_position_error", &J::is_object, "an object");
        if (const auto rms = error.find("rms");
            rms == error.end() || !(rms->is_number() || rms->is_null()))
          throw InputError(p.file + ": " + pt +
                           ".final_position_error.rms: should be a number or null");
        if (points[k].contains("verdict"))
          field(p, points[k], pt, "verdict", &J::is_string, "a string");
      }
    }
  } else {
    const J& cases = field(p, p.json, "", "cases", &J::is_array, "an array");
    for (std::size_t c = 0; c < cases.size(); ++c) {
      const std::string at = "cases[" + std::to_string(c) + "]";
      if (!cases[c].is_object())
        throw InputError(p.file + ": " + at + ": should be an object, got " + cases[c].type_name());
      field(p, cases[c], at, "case", &J::is_string, "a string");
      field(p, cases[c], at, "engine", &J::is_string, "a string");
      field(p, cases[c], at, "verdict", &J::is_string, "a string");
      field(p, cases[c], at, "fatal", &J::is_boolean, "true or false");
    }
  }
}

Block read_block(const ShardPart& p) {
  const ordered_json& j = p.json;
  if (!j.is_object() || !j.contains("shard")) {
    throw InputError(p.file +
                     ": not a part of a sharded run (no \"shard\" block: written "
                     "without --shard K/N?)");
  }
  const ordered_json& s = j["shard"];
  if (!s.is_object())
    throw InputError(p.file + ": shard: should be an object, got " + std::string(s.type_name()));
  using J = ordered_json;
  field(p, s, "shard", "command", &J::is_string, "a string");
  field(p, s, "shard", "version", &J::is_string, "a string");
  field(p, s, "shard", "grid", &J::is_string, "a string");
  for (const char* key : {"index", "count", "units"})
    field(p, s, "shard", key, &J::is_number_integer, "a whole number");
  // Whole numbers in [lo, 2^31 - 1], read without narrowing (4294967298 is not 2).
  constexpr long long kMaxWhole = 2147483647;
  auto whole = [&](const J& v, const std::string& name, long long lo) -> long long {
    const bool fits = v.is_number_unsigned()
                          ? v.get<std::uint64_t>() <= static_cast<std::uint64_t>(kMaxWhole)
                          : v.get<long long>() >= lo && v.get<long long>() <= kMaxWhole;
    if (!fits) {
      throw InputError(p.file + ": " + name + ": " + v.dump() + " is outside [" +
                       std::to_string(lo) + ", " + std::to_string(kMaxWhole) + "]");
    }
    return v.get<long long>();
  };
  Block b;
  b.command = s.at("command").get<std::string>();
  b.version = s.at("version").get<std::string>();
  b.grid = s.at("grid").get<std::string>();
  // index and count below 1 are refused further on, with what they should be.
  b.index = static_cast<int>(whole(s.at("index"), "shard.index", -kMaxWhole));
  b.count = static_cast<int>(whole(s.at("count"), "shard.count", -kMaxWhole));
  b.units = static_cast<std::size_t>(whole(s.at("units"), "shard.units", 0));
  std::set<std::size_t> listed;
  for (const J& u : field(p, s, "shard", "ran", &J::is_array, "an array")) {
    if (!u.is_number_integer())
      throw InputError(p.file + ": shard.ran: should hold whole numbers, got " +
                       std::string(u.type_name()));
    const auto unit = static_cast<std::size_t>(whole(u, "shard.ran", 0));
    if (!listed.insert(unit).second)
      throw InputError(p.file + ": shard.ran: unit " + std::to_string(unit) + " listed twice");
    b.ran.push_back(unit);
  }
  const std::string schema = j.value("schema", "");
  if (schema != "chainbench." + b.command + "/1" || (b.command != "sweep" && b.command != "stress"))
    throw InputError(p.file + ": a part of \"" + b.command + "\" with schema \"" + schema +
                     "\": only sweep and stress parts merge");
  check_results(p, b.command);
  if (b.count < 1 || b.index < 1 || b.index > b.count)
    throw InputError(p.file + ": shard " + std::to_string(b.index) + "/" + std::to_string(b.count) +
                     " is not a part of its whole");
  for (const std::size_t u : b.ran) {
    if (u >= b.units ||
        u % static_cast<std::size_t>(b.count) != static_cast<std::size_t>(b.index - 1))
      throw InputError(p.file + ": unit " + std::to_string(u) + " does not belong to part " +
                       std::to_string(b.index) + "/" + std::to_string(b.count));
  }
  return b;
}

std::string part_name(const Block& b) {
  return std::to_string(b.index) + "/" + std::to_string(b.count);
}

// Every part of one whole, each once: else what is wrong, naming the files.
void check_whole(const std::vector<ShardPart>& parts, const std::vector<Block>& blocks) {
  const Block& a = blocks.front();
  const std::string& first = parts.front().file;
  for (std::size_t k = 1; k < parts.size(); ++k) {
    const Block& b = blocks[k];
    const std::string& f = parts[k].file;
    if (b.command != a.command)
      throw InputError(f + ": a part of a " + b.command + ", but " + first + " is a part of a " +
                       a.command);
    if (b.version != a.version)
      throw InputError(f + ": written by chainbench " + b.version + ", but " + first + " by " +
                       a.version + ": parts must come from one version");
    if (b.grid != a.grid || b.units != a.units)
      throw InputError(f + ": a part of another " + b.command +
                       " (its scenes, engines or "
                       "settings differ: grid " +
                       b.grid + ", " + std::to_string(b.units) + " units) than " + first +
                       " (grid " + a.grid + ", " + std::to_string(a.units) + " units)");
    if (b.count != a.count)
      throw InputError(f + ": part " + part_name(b) + ", but " + first + " is part " +
                       part_name(a) + ": the whole was cut into parts two ways");
  }
  std::map<int, std::string> seen;
  for (std::size_t k = 0; k < parts.size(); ++k) {
    const auto [at, fresh] = seen.emplace(blocks[k].index, parts[k].file);
    if (!fresh)
      throw InputError(parts[k].file + ": part " + part_name(blocks[k]) + " again (also " +
                       at->second + ")");
  }
  std::string missing;
  for (int i = 1; i <= a.count; ++i) {
    if (!seen.count(i))
      missing += (missing.empty() ? "" : ", ") + std::to_string(i) + "/" + std::to_string(a.count);
  }
  if (!missing.empty()) throw InputError("merge: part(s) " + missing + " missing");
}

// Sweep points compete for the Pareto front only on what the JSON keeps of them.
VerdictClass verdict_named(const std::string& name) {
  for (int c = 0; c <= static_cast<int>(VerdictClass::kCrash); ++c) {
    if (name == to_string(static_cast<VerdictClass>(c))) return static_cast<VerdictClass>(c);
  }
  return VerdictClass::kOk;
}

void mark_front(ordered_json& points) {
  std::vector<SweepPoint> front(points.size());
  for (std::size_t k = 0; k < points.size(); ++k) {
    const ordered_json& p = points[k];
    SweepPoint& s = front[k];
    s.run.timing.median_ms = p.value("ms_per_step", 0.0);
    s.run.timing.spread_ms = p.value("ms_spread", 0.0);
    const ordered_json& rms = p["final_position_error"]["rms"];
    s.error.rms = rms.is_number() ? rms.get<double>() : HUGE_VAL;
    if (p.contains("verdict"))
      s.run.verdict = Verdict{verdict_named(p["verdict"].get<std::string>()), {}};
  }
  mark_pareto(front);
  for (std::size_t k = 0; k < points.size(); ++k)
    points[k]["pareto"] = front[k].pareto;
}

// Merges the parts' results, each list of `key` (points of each scene, or cases), into `whole`,
// ordered by unit.
Merged merge_sweep(const std::vector<ShardPart>& parts, const std::vector<Block>& blocks) {
  Merged m;
  m.json = parts.front().json;
  m.json.erase("shard");
  ordered_json& scenes = m.json["scenes"];
  std::vector<std::map<std::size_t, ordered_json>> points(scenes.size());
  for (std::size_t k = 0; k < parts.size(); ++k) {
    const ordered_json& part_scenes = parts[k].json["scenes"];
    if (part_scenes.size() != scenes.size())
      throw InputError(parts[k].file + ": " + std::to_string(part_scenes.size()) + " scenes, but " +
                       parts.front().file + " has " + std::to_string(scenes.size()));
    std::size_t next = 0;  // into the part's units
    for (std::size_t s = 0; s < scenes.size(); ++s) {
      const ordered_json& ps = part_scenes[s];
      for (const ordered_json& p : ps["points"]) {
        if (next == blocks[k].ran.size())
          throw InputError(parts[k].file + ": holds more points than the units it names");
        points[s][blocks[k].ran[next++]] = p;
      }
      if (ps.value("interrupted", false)) scenes[s]["interrupted"] = true;
      if (ps.contains("reference_ms_per_step") && !scenes[s].contains("reference_ms_per_step")) {
        // Keep the key where the unsharded JSON has it: before "interrupted".
        ordered_json header;
        for (auto it = scenes[s].begin(); it != scenes[s].end(); ++it) {
          if (it.key() == "interrupted")
            header["reference_ms_per_step"] = ps["reference_ms_per_step"];
          header[it.key()] = it.value();
        }
        scenes[s] = std::move(header);
      }
    }
    if (next != blocks[k].ran.size())
      throw InputError(parts[k].file + ": names " + std::to_string(blocks[k].ran.size()) +
                       " units but holds " + std::to_string(next) + " points");
  }
  for (std::size_t s = 0; s < scenes.size(); ++s) {
    ordered_json list = ordered_json::array();
    for (auto& [unit, p] : points[s])
      list.push_back(std::move(p));
    mark_front(list);
    m.units += list.size();
    scenes[s]["points"] = std::move(list);
  }
  return m;
}

Merged merge_stress(const std::vector<ShardPart>& parts, const std::vector<Block>& blocks) {
  Merged m;
  m.json = parts.front().json;
  m.json.erase("shard");
  std::map<std::size_t, ordered_json> cases;
  for (std::size_t k = 0; k < parts.size(); ++k) {
    const ordered_json& list = parts[k].json["cases"];
    if (list.size() != blocks[k].ran.size())
      throw InputError(parts[k].file + ": names " + std::to_string(blocks[k].ran.size()) +
                       " units but holds " + std::to_string(list.size()) + " cases");
    if (parts[k].json.value("quick", false) != m.json.value("quick", false))
      throw InputError(parts[k].file + ": --quick differs from " + parts.front().file);
    for (std::size_t c = 0; c < list.size(); ++c)
      cases[blocks[k].ran[c]] = list[c];
    if (parts[k].json.value("interrupted", false)) m.json["interrupted"] = true;
  }
  ordered_json list = ordered_json::array();
  for (auto& [unit, c] : cases) {
    m.fatal += c.value("fatal", false) ? 1 : 0;
    list.push_back(std::move(c));
  }
  m.units = list.size();
  m.json["cases"] = std::move(list);
  return m;
}

}  // namespace

Merged merge_parts(const std::vector<ShardPart>& parts) {
  if (parts.empty()) throw InputError("merge: give the parts' JSON files");
  std::vector<Block> blocks;
  for (const ShardPart& p : parts)
    blocks.push_back(read_block(p));
  check_whole(parts, blocks);
  Merged m =
      blocks.front().command == "sweep" ? merge_sweep(parts, blocks) : merge_stress(parts, blocks);
  m.command = blocks.front().command;
  if (m.units != blocks.front().units) {
    throw InputError("merge: the parts hold " + std::to_string(m.units) + " of the " +
                     std::to_string(blocks.front().units) +
                     " units of the whole (was a part interrupted?)");
  }
  return m;
}

}  // namespace chainbench
