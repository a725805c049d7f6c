// SPDX-License-Identifier: MIT
// The text of a scene file beyond what JSON itself requires: the file's bytes as a whole, and each
// string field (a scene's, body's or expectation's name, a description, a type). A name reaches
// the run table, findings, CSV, traces and replay pages, so it must be text a terminal and a CSV
// reader show as written: UTF-8 without control characters, and short enough to read.
#pragma once

#include <cstddef>
#include <string>

namespace chainbench {

// The most bytes a name may hold (scene, body and every other string field but the
// description), and the description.
inline constexpr std::size_t kMaxSceneNameBytes = 256;
inline constexpr std::size_t kMaxSceneDescriptionBytes = 4096;

// Empty when a scene file's bytes may be read as JSON; else why not, naming the byte: a NUL byte
// anywhere (never part of JSON text, and the JSON reader would stop there and ignore the rest),
// or a UTF-16 or UTF-32 byte order mark (scene files are UTF-8). A UTF-8 byte order mark at the
// start is accepted and skipped: RFC 8259 §8.1 allows a reader to ignore it, and some editors
// write it; it carries no content.
std::string scene_bytes_problem(const std::string& text);

// Empty when `value` may be a string field of at most `max_bytes` bytes; else the reason, which
// never echoes the value: "is 52428800 bytes, more than the 256 a name may hold", or
// text_problem's "holds the byte 0x1b at offset 3 (...)". Linear in the value, and the length
// is checked first.
std::string scene_text_problem(const std::string& value, std::size_t max_bytes, const char* what);

}  // namespace chainbench
