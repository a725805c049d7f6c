// SPDX-License-Identifier: MIT
#include "support/number_text.h"

#include <charconv>
#include <cmath>

namespace chainbench {

void append_exact_number(std::string& out, double v) {
  if (std::isnan(v)) {
    out += "nan";
    return;
  }
  if (std::isinf(v)) {
    out += v > 0 ? "inf" : "-inf";
    return;
  }
  char buf[32];
  // to_chars' plain form of a whole number below 1e15 is its every digit; elsewhere it picks the
  // shorter of the plain and scientific forms that read back exactly.
  const bool whole = v == std::floor(v) && std::fabs(v) < 1e15;
  const auto r = whole ? std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed)
                       : std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, r.ptr);
}

std::string exact_number(double v) {
  std::string out;
  append_exact_number(out, v);
  return out;
}

}  // namespace chainbench
