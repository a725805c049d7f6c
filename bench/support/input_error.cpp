#include "input_error.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>

namespace chainbench {

double parse_number(const std::string& what, const std::string& text) {
  const char* begin = text.c_str();
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(begin, &end);
  if (text.empty() || end != begin + text.size()) {
    throw InputError(what + ": \"" + text + "\" is not a number");
  }
  if (!std::isfinite(v) || errno == ERANGE) {
    throw InputError(what + ": \"" + text + "\" is not a finite number in double range");
  }
  return v;
}

long long parse_integer(const std::string& what, const std::string& text, long long lo,
                        long long hi) {
  const double v = parse_number(what, text);
  if (v != std::floor(v)) throw InputError(what + ": \"" + text + "\" is not a whole number");
  if (v < static_cast<double>(lo) || v > static_cast<double>(hi)) {
    throw InputError(what + ": " + text + " is out of range [" + std::to_string(lo) + ", " +
                     std::to_string(hi) + "]");
  }
  return static_cast<long long>(v);
}

}  // namespace chainbench
