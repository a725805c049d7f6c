// SPDX-License-Identifier: MIT
// chainbench merge: joins the parts of a sharded sweep or stress run (merge.h).
#include "campaign/merge.h"
#include "cli/commands.h"
#include "cli/value_checks.h"
#include "support/input_error.h"
#include "support/output_file.h"

#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>

namespace chainbench {
namespace {

struct MergeArgs {
  std::vector<std::string> files;
  std::string json;
};

ShardPart read_part(const std::string& file) {
  if (std::filesystem::is_directory(file)) throw InputError(file + ": is a directory");
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file + ": cannot read");
  ShardPart p{file, {}};
  // A part is a few levels deep; a deeper one is refused as it is read, before anything walks
  // it recursively (nlohmann's dump does).
  constexpr int kMaxDepth = 64;
  const auto limit = [&](int depth, nlohmann::ordered_json::parse_event_t,
                         nlohmann::ordered_json&) {
    if (depth > kMaxDepth) {
      throw InputError(file + ": nested deeper than " + std::to_string(kMaxDepth) +
                       " levels: not a part of a sharded run");
    }
    return true;
  };
  try {
    p.json = nlohmann::ordered_json::parse(in, limit);
  } catch (const nlohmann::json::parse_error& e) {
    throw InputError(file + ": not JSON (" + e.what() + ")");
  } catch (const nlohmann::json::out_of_range& e) {
    // 406: a number such as 1e400, beyond double range.
    throw InputError(file + ": holds a number beyond double range (" + e.what() + ")");
  }
  return p;
}

int run(const MergeArgs& a) {
  std::vector<ShardPart> parts;
  for (const std::string& file : a.files)
    parts.push_back(read_part(file));
  const Merged merged = merge_parts(parts);
  auto json_out = open_output(a.json, "--json");
  const std::string text = merged.json.dump(2) + "\n";
  if (json_out) {
    json_out->stream() << text;
    commit_outputs({json_out.get()});
  } else {
    std::cout << text;
  }
  // The summary goes where the JSON does not.
  std::ostream& note = json_out ? std::cout : std::cerr;
  note << "merged " << parts.size() << " parts of a " << merged.command << ": " << merged.units
       << (merged.command == "sweep" ? " points" : " runs");
  if (merged.command == "stress")
    note << ", " << merged.fatal << " failing the matrix (as the unsharded run's exit status)";
  note << '\n';
  return merged.fatal > 0 ? 1 : 0;
}

}  // namespace

void add_merge_command(CLI::App& app, int* status) {
  auto args = std::make_shared<MergeArgs>();
  CLI::App* m = app.add_subcommand(
      "merge", "Join the JSON parts of a sharded sweep or stress run (--shard K/N) into one");
  m->add_option("files", args->files, "the parts' JSON files, every part once, in any order")
      ->required();
  m->add_option("--json", args->json, "write the joined JSON here (default: standard output)")
      ->check(non_empty_path("output file"));
  m->footer(
      "The joined JSON is what the unsharded command writes, point for point (timings are each "
      "part's own; a sweep's Pareto marks are computed again over the whole).\nExit status: 0 "
      "joined; 2 a file that is not a part, parts of different commands, versions or grids, a "
      "part given twice or missing; 1 (stress) some run fails the matrix, as the unsharded "
      "command would exit.");
  m->callback([args, status] {
    std::vector<NamedFile> inputs;
    for (const std::string& file : args->files)
      inputs.emplace_back("part", &file);
    refuse_clashing_files({{"--json", &args->json}}, inputs);
    *status = run(*args);
  });
}

}  // namespace chainbench
