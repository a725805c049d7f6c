// SPDX-License-Identifier: MIT
// Bad input from the user: a scene file, a --set, an engine spec, a command-line number. The
// message names the source, the field and the reason; the command exits with status 2.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>

namespace chainbench {

class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// `text` as a message may echo it: whole up to `shown` bytes, else its first `shown` and
// "…(N bytes)"; control characters, invisible or text-reordering characters (U+200B-U+200F,
// U+2028-U+202E, U+2060-U+206F, U+FEFF, U+FFF9-U+FFFB, U+FFFE, U+FFFF) and bytes that are not
// UTF-8 are shown as \xNN.
std::string cut_for_message(const std::string& text, std::size_t shown = 80);
// Empty when `text` is UTF-8 without control or invisible characters (as cut_for_message shows
// them); else which byte is not, and where.
std::string text_problem(const std::string& text);
// Parses all of `text` as a finite number, in the grammar of std::from_chars as every
// command-line number (no '+', blanks or hexadecimal), or throws InputError("<what>: ...").
double parse_number(const std::string& what, const std::string& text);
// Parses all of `text` as an integer in [lo, hi], or throws InputError("<what>: ...").
long long parse_integer(const std::string& what, const std::string& text, long long lo,
                        long long hi);

}  // namespace chainbench
