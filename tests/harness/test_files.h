// SPDX-License-Identifier: MIT
// Files for tests that write and read outputs: a folder of a test's own, and a file's bytes.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace chainbench::test {

// The folder NAME under GoogleTest's temporary directory, emptied and made anew; with a
// trailing '/', so that a file's path is folder + its name.
inline std::string fresh_folder(const std::string& name) {
  const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir.string() + "/";
}

// Every byte of the file at `path`; empty when it cannot be read.
inline std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace chainbench::test
