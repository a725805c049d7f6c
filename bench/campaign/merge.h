// SPDX-License-Identifier: MIT
// `chainbench merge`: joins the parts of a sharded sweep or stress run (shard.h) into the JSON the
// unsharded command writes: the same keys in the same order, every point or run in its place.
// Timings are each part's own, and a sweep's Pareto marks are computed again over the whole.
#pragma once

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace chainbench {

struct ShardPart {
  std::string file;  // for messages
  nlohmann::ordered_json json;
};

struct Merged {
  nlohmann::ordered_json json;  // as the unsharded command writes it
  std::string command;          // "sweep" or "stress"
  std::size_t units = 0;
  int fatal = 0;  // stress: runs that fail the matrix (the unsharded command would exit 1)
};

// Throws InputError naming the file and the reason when a part is not a part (no "shard"
// block), parts come from different commands, versions or grids, a part is given twice, a part
// is missing, or a part does not hold the units it names.
Merged merge_parts(const std::vector<ShardPart>& parts);

}  // namespace chainbench
