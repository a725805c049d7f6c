// SPDX-License-Identifier: MIT
#include "scenes/scene_text.h"

#include "support/input_error.h"

#include <cstring>

namespace chainbench {

std::string scene_bytes_problem(const std::string& text) {
  const auto starts = [&](const char* bom, std::size_t n) {
    return text.size() >= n && std::memcmp(text.data(), bom, n) == 0;
  };
  if (starts("\xff\xfe", 2) || starts("\xfe\xff", 2)) {
    return "starts with a UTF-16 or UTF-32 byte order mark: scene files are UTF-8";
  }
  if (const auto nul = text.find('\0'); nul != std::string::npos) {
    return "holds a NUL byte at offset " + std::to_string(nul) +
           " (a scene file is JSON text, which has none; a file cut or padded by a tool?)";
  }
  return "";
}

std::string scene_text_problem(const std::string& value, std::size_t max_bytes, const char* what) {
  if (value.size() > max_bytes) {
    return "is " + std::to_string(value.size()) + " bytes, more than the " +
           std::to_string(max_bytes) + " " + what + " may hold";
  }
  return text_problem(value);
}

}  // namespace chainbench
