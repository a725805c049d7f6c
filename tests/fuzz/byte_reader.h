// SPDX-License-Identifier: MIT
// Turns a fuzzer's bytes into bounded numbers. Past the end it returns zeros, so every input,
// however short, describes a complete (small) case.
#pragma once

#include <cstddef>
#include <cstdint>

namespace fuzz {

class ByteReader {
 public:
  ByteReader(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}

  std::uint8_t byte() { return at_ < size_ ? data_[at_++] : 0; }
  bool flag() { return (byte() & 1u) != 0; }
  // One of n choices, n in [1, 256].
  int pick(int n) { return static_cast<int>(byte() % static_cast<unsigned>(n)); }
  // lo + k * step for a byte k: values on a grid make exact touching and stacking likely,
  // which is where a resolver's edge cases are.
  double grid(double lo, double step) { return lo + step * byte(); }
  // 10^e for a whole e in [lo_exp, hi_exp]: the extreme ratios, one byte each.
  double decades(int lo_exp, int hi_exp) {
    const int e = lo_exp + pick(hi_exp - lo_exp + 1);
    double value = 1.0;  // repeated products: the same bits with every libm
    for (int i = 0; i < (e < 0 ? -e : e); ++i)
      value *= 10.0;
    return e < 0 ? 1.0 / value : value;
  }
  bool exhausted() const { return at_ >= size_; }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t at_ = 0;
};

}  // namespace fuzz
