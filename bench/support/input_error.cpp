// SPDX-License-Identifier: MIT
#include "support/input_error.h"

#include <charconv>
#include <cmath>
#include <system_error>

namespace chainbench {

namespace {

// The length of the well-formed UTF-8 character at text[i], or 0 when none starts there.
std::size_t utf8_length(const std::string& text, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char lead = byte(i);
  const std::size_t n = lead < 0x80u           ? 1
                        : (lead >> 5) == 0x6u  ? 2
                        : (lead >> 4) == 0xeu  ? 3
                        : (lead >> 3) == 0x1eu ? 4
                                               : 0;
  if (n == 0 || i + n > text.size()) return 0;
  for (std::size_t k = 1; k < n; ++k) {
    if ((byte(i + k) & 0xc0u) != 0x80u) return 0;
  }
  if (n == 2 && lead < 0xc2u) return 0;                           // overlong
  if (n == 3 && lead == 0xe0u && byte(i + 1) < 0xa0u) return 0;   // overlong
  if (n == 3 && lead == 0xedu && byte(i + 1) >= 0xa0u) return 0;  // a UTF-16 surrogate
  if (n == 4 && (lead > 0xf4u || (lead == 0xf0u && byte(i + 1) < 0x90u))) return 0;
  if (n == 4 && lead == 0xf4u && byte(i + 1) >= 0x90u) return 0;  // above U+10FFFF
  return n;
}

bool control(unsigned char c) {
  return c < 0x20u || c == 0x7fu;
}

// The code point of the well-formed UTF-8 character of n bytes at text[i].
char32_t code_point(const std::string& text, std::size_t i, std::size_t n) {
  const auto byte = [&](std::size_t k) {
    return static_cast<char32_t>(static_cast<unsigned char>(text[k]));
  };
  char32_t c = byte(i) & (n == 1 ? 0x7fu : n == 2 ? 0x1fu : n == 3 ? 0x0fu : 0x07u);
  for (std::size_t k = 1; k < n; ++k)
    c = (c << 6) | (byte(i + k) & 0x3fu);
  return c;
}

// Characters that show nothing or change how the text around them is shown: zero-width
// characters and joiners, bidirectional marks, embeddings, overrides and isolates (U+202E turns
// what follows around), line and paragraph separators (a line break to a terminal), the
// invisible operators, an in-text byte order mark, the interlinear annotation controls, and the
// noncharacters U+FFFE and U+FFFF.
bool invisible(char32_t c) {
  return (c >= 0x200bu && c <= 0x200fu) || (c >= 0x2028u && c <= 0x202eu) ||
         (c >= 0x2060u && c <= 0x206fu) || c == 0xfeffu || (c >= 0xfff9u && c <= 0xfffbu) ||
         c == 0xfffeu || c == 0xffffu;
}

// Whether text[i] starts no character a message may show: a byte that starts no well-formed
// UTF-8 character, a C0 control or DEL, a C1 control (U+0080-U+009F, which some terminals obey
// as escapes), or a character that is invisible or reorders the text (invisible()).
bool unshown(const std::string& text, std::size_t i, std::size_t n) {
  if (n == 0) return true;
  if (n == 1) return control(static_cast<unsigned char>(text[i]));
  const char32_t c = code_point(text, i, n);
  return (c >= 0x80u && c <= 0x9fu) || invisible(c);
}

}  // namespace

std::string text_problem(const std::string& text) {
  for (std::size_t i = 0; i < text.size();) {
    const std::size_t n = utf8_length(text, i);
    if (unshown(text, i, n)) {
      constexpr char kHex[] = "0123456789abcdef";
      const auto c = static_cast<unsigned char>(text[i]);
      return std::string("holds the byte 0x") + kHex[c >> 4] + kHex[c & 15u] + " at offset " +
             std::to_string(i) + " (text here is UTF-8 without control or invisible characters)";
    }
    i += n;
  }
  return "";
}

std::string cut_for_message(const std::string& text, std::size_t shown) {
  std::string out;
  std::size_t i = 0;
  while (i < text.size() && i < shown) {
    const std::size_t n = utf8_length(text, i);
    if (unshown(text, i, n)) {
      // Shown as \xNN, so that an echoed input can neither drive the terminal nor make an
      // output file that is not UTF-8.
      constexpr char kHex[] = "0123456789abcdef";
      const auto c = static_cast<unsigned char>(text[i]);
      out += "\\x";
      out += kHex[c >> 4];
      out += kHex[c & 15u];
      ++i;
    } else {
      out.append(text, i, n);  // whole characters only: a cut never leaves half of one
      i += n;
    }
  }
  if (i < text.size()) out += "\u2026(" + std::to_string(text.size()) + " bytes)";
  return out;
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
