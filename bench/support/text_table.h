// SPDX-License-Identifier: MIT
// A plain-text table with aligned columns, for terminal reports.
#pragma once

#include <cstddef>
#include <initializer_list>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

namespace chainbench {

class TextTable {
 public:
  explicit TextTable(std::vector<std::string> header) : rows_{std::move(header)} {}
  void add(std::vector<std::string> row) { rows_.push_back(std::move(row)); }
  // A table of text (keys and their help, not numbers): every column left-aligned and, where the
  // table is wider than `width`, columns narrowed and their cells wrapped at spaces onto lines of
  // their own column until it fits: first the last one, down to kMinWrapped characters (a longer
  // word cut across lines), then the widest of the others in turn, each down to its longest word
  // (a table that cannot fit so is left wider). The first column never wraps. Without it the first
  // column is left-aligned, the others right.
  void wrap_text(std::size_t width) { wrap_ = width; }
  void print(std::ostream& out) const;

  static constexpr std::size_t kMinWrapped = 24;

 private:
  std::vector<std::vector<std::string>> rows_;
  std::size_t wrap_ = 0;  // 0: numbers, right-aligned, never wrapped
};

// The parts joined into one string. (Long operator+ chains on std::string trip GCC 12's
// -Wrestrict at -O3 with a false report.)
std::string concat(std::initializer_list<std::string_view> parts);

// Short renderings for tables: "0.0123", "1.2e-07", "-" for missing.
std::string fmt_g(double v, int digits = 3);
// The significant digits, `at_least` or more (up to 17), at which fmt_g writes a and b apart: a
// measure beside the limit it broke must not read as equal to it ("0.15855 m beyond its
// 0.1585 m", not "0.159 ... 0.159"). at_least when they are equal.
int digits_apart(double a, double b, int at_least = 3);
// A limit beside the measure that broke it, the measure written to `digits` (digits_apart): to 3
// digits where those already tell them apart, else exactly, as it was given (exact_number), so
// that a limit of 1.99999999 never reads as 2.
std::string fmt_limit(double limit, int digits);
std::string fmt_ms(double ms);

}  // namespace chainbench
