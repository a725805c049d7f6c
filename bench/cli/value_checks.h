// SPDX-License-Identifier: MIT
// Checks of numeric option values whose messages say what is wrong: CLI11's own Range reports a
// value that is not a number at all as "not in range".
#pragma once

#include <CLI/CLI.hpp>

#include <charconv>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <string>
#include <system_error>

namespace chainbench {

// A whole number in [lo, hi], written in any form whose value is whole ("1000", "1e3",
// "1000.0"); the text is rewritten to the integer, since CLI11 converts it after this check:
// give it with ->transform(), as ->check() keeps the text as typed.
inline CLI::Validator whole_number_in(std::int64_t lo, std::int64_t hi) {
  const std::string range = "[" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
  return CLI::Validator(
      [lo, hi, range](std::string& text) -> std::string {
        // Read as a double: every whole number of the ranges used (up to 1e7) is exact in one.
        double v = 0.0;
        const char* end = text.data() + text.size();
        const auto [at, ec] = std::from_chars(text.data(), end, v);
        if (text.empty() || at != end || ec == std::errc::invalid_argument || std::isnan(v) ||
            (std::isfinite(v) && v != std::floor(v)))
          return "\"" + text + "\" is not a whole number";
        if (ec == std::errc::result_out_of_range || v < static_cast<double>(lo) ||
            v > static_cast<double>(hi))
          return text + " is outside " + range;
        text = std::to_string(static_cast<std::int64_t>(v));
        return {};
      },
      range);
}

// A path that is not empty: an empty one would otherwise be taken as "not given" further on.
inline CLI::Validator non_empty_path(const std::string& what) {
  return CLI::Validator(
      [what](std::string& text) -> std::string {
        return text.empty() ? "the " + what + " path is empty" : std::string();
      },
      "");
}

// Text that is not empty, for an option whose empty value would otherwise read as "not given".
inline CLI::Validator non_empty_text(const std::string& option, const std::string& form) {
  return CLI::Validator(
      [option, form](std::string& text) -> std::string {
        return text.empty() ? option + " is empty: give " + form : std::string();
      },
      "");
}

// A finite number in [lo, hi].
inline CLI::Validator number_in(double lo, double hi) {
  std::ostringstream r;
  r << "[" << lo << ", " << hi << "]";
  const std::string range = r.str();
  return CLI::Validator(
      [lo, hi, range](std::string& text) -> std::string {
        double v = 0.0;
        const char* end = text.data() + text.size();
        const auto [at, ec] = std::from_chars(text.data(), end, v);
        if (text.empty() || at != end || ec == std::errc::invalid_argument)
          return "\"" + text + "\" is not a number";
        if (ec == std::errc::result_out_of_range || !std::isfinite(v) || v < lo || v > hi)
          return text + " is outside " + range;
        return {};
      },
      range);
}

// --timeout SECONDS of run, sweep and stress, one range for all: a millisecond to a day.
inline CLI::Validator timeout_seconds() {
  return number_in(0.001, 86400.0);
}

}  // namespace chainbench
