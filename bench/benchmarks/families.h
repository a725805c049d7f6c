// SPDX-License-Identifier: MIT
// What chainbench_bench times: scene families, each a built-in scene at a list of sizes, how its
// steps are timed, and which of them the results tables treat as moving scenes or scaling series.
#pragma once

#include <cstddef>
#include <limits>
#include <string>
#include <vector>

namespace chainbench {

struct Family {
  std::string name;  // the benchmark's first name part
  std::string scene;
  std::vector<std::string> size_keys;  // --set keys each given the size (rows and cols), or none
  std::vector<int> sizes;              // values of the size keys ({0} when there are none)
  std::vector<std::string> sets;       // fixed --set values
  int warmup = 30;                     // steps before the timing starts
  // 0: steps are timed for as long as Google Benchmark needs (the world at rest, every step alike).
  // > 0: exactly this many steps are timed after the warm-up, in a scene built for
  // warmup + window steps, so that every engine does the same work (a moving scene).
  int window = 0;
  bool moving = false;  // the README headline's scenes
  // Engines other than the one under test run only at sizes up to this many bodies.
  std::size_t others_max = std::numeric_limits<std::size_t>::max();
  // For the scaling table: the size every other is compared with (about 5-10k bodies), or 0.
  int scaling_base = 0;
};

const std::vector<Family>& benchmark_families();

// The family's --set values at `size`: its own sets, the size keys, and the run length.
std::vector<std::string> family_sets(const Family& family, int size);
// Bodies of the family's scene at `size`, without building it.
std::size_t family_bodies(const Family& family, int size);

}  // namespace chainbench
