// SPDX-License-Identifier: MIT
// One part of a sweep grid or stress matrix, run where the user sends it (`--shard K/N`): the
// units of the whole (sweep points, stress case x engine runs, numbered from 0 in the order the
// unsharded command runs them) whose number u has u % N == K - 1. A part's JSON holds the
// unsharded JSON's keys for its units plus a "shard" block naming the command, the version,
// a fingerprint of the whole grid and its units, so that `chainbench merge` (merge.h) joins only
// parts of one whole, and all of them.
#pragma once

#include "engines/engine_spec.h"
#include "model/scene.h"

#include <nlohmann/json.hpp>

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace chainbench {

struct Shard {
  int index = 1;  // K, 1-based
  int count = 1;  // N; 1: the whole
  bool whole() const { return count == 1; }
  bool has(std::size_t unit) const {
    return unit % static_cast<std::size_t>(count) == static_cast<std::size_t>(index - 1);
  }
};

// "K/N" with 1 <= K <= N <= 100000, else InputError naming --shard.
Shard parse_shard(const std::string& text);

// What a part is a part of: a command's name, the version of the chainbench that ran it, and a
// text naming every unit of the whole (scenes by their full contents, engine specs, reference,
// timeout...), kept as a 64-bit fingerprint.
struct ShardOrigin {
  std::string command;  // "sweep", "stress"
  std::string version;
  std::string grid;  // the fingerprint, hex
  std::size_t units = 0;
};

// A fingerprint of everything in a scene that a run depends on.
std::string scene_identity(const Scene& scene);
// The fingerprint of a description of the whole, hex.
std::string grid_fingerprint(std::string_view description);

// The "shard" block of a part's JSON: the origin, K, N and the units it ran, in the order its
// results appear.
nlohmann::ordered_json shard_json(const ShardOrigin& origin, const Shard& shard,
                                  const std::vector<std::size_t>& units);

}  // namespace chainbench
