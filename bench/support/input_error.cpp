#include "input_error.h"

#include <charconv>
#include <cmath>
#include <system_error>

namespace chainbench {

std::string cut_for_message(const std::string& text) {
  constexpr std::size_t kShown = 80;
  if (text.size() <= kShown) return text;
  // Cut at a UTF-8 character boundary, so that the cut never leaves half a character.
  std::size_t end = kShown;
  while (end > 0 && (static_cast<unsigned char>(text[end]) & 0xc0u) == 0x80u)
    --end;
  return text.substr(0, end) + "\u2026(" + std::to_string(text.size()) + " bytes)";
}

double parse_number(const std::string& what, const std::string& text) {
  // std::from_chars, as every command-line number is read (value_checks.h): no sign but '-', no
  // blanks, no hexadecimal, nothing after the number.
  double v = 0.0;
  const char* end = text.data() + text.size();
  const auto [at, ec] = std::from_chars(text.data(), end, v);
  if (text.empty() || at != end || ec == std::errc::invalid_argument) {
    throw InputError(what + ": \"" + cut_for_message(text) + "\" is not a number");
  }
  if (ec == std::errc::result_out_of_range || !std::isfinite(v)) {
    throw InputError(what + ": \"" + cut_for_message(text) +
                     "\" is not a finite number in double range");
  }
  return v;
}

long long parse_integer(const std::string& what, const std::string& text, long long lo,
                        long long hi) {
  const double v = parse_number(what, text);
  if (v != std::floor(v))
    throw InputError(what + ": \"" + cut_for_message(text) + "\" is not a whole number");
  if (v < static_cast<double>(lo) || v > static_cast<double>(hi)) {
    throw InputError(what + ": " + cut_for_message(text) + " is out of range [" +
                     std::to_string(lo) + ", " + std::to_string(hi) + "]");
  }
  return static_cast<long long>(v);
}

}  // namespace chainbench
