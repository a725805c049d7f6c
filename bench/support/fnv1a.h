// SPDX-License-Identifier: MIT
// FNV-1a, 64 bit: the one hash the harness prints (final positions, shard fingerprints), the same
// on every machine, compiler and run.
#pragma once

#include <bit>
#include <cstdint>
#include <string_view>

namespace chainbench {

struct Fnv1a {
  std::uint64_t value = 0xcbf29ce484222325ull;  // the offset basis

  void add(unsigned char byte) {
    value ^= byte;
    value *= 0x100000001b3ull;  // the FNV prime
  }
  void add(std::string_view bytes) {
    for (const char c : bytes)
      add(static_cast<unsigned char>(c));
  }
  // The double's IEEE-754 bit pattern, least significant byte first (any host's byte order).
  void add_bits(double v) {
    const auto bits = std::bit_cast<std::uint64_t>(v);
    for (int k = 0; k < 8; ++k)
      add(static_cast<unsigned char>((bits >> (8 * k)) & 0xffu));
  }
};

}  // namespace chainbench
