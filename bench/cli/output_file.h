// The files a command writes (--json, --csv, --trace). Each is opened before anything runs, so a
// path that cannot be written is refused at once (exit 2), and flushed at the end, so that a full
// disk is reported rather than left as a short file.
#pragma once

#include <fstream>
#include <initializer_list>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>

namespace chainbench {

// An output file could not be written in full (a full disk, a device error); exit status 1.
class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The file at `path`, emptied, or null if `path` is empty; InputError ("<option>: cannot write
// <path>") if it cannot be opened.
std::unique_ptr<std::ofstream> open_output(const std::string& path, const char* option);
// InputError if two of the outputs (option, path; empty paths are not given) name the same file:
// the second would overwrite the first.
void refuse_shared_outputs(
    std::initializer_list<std::pair<const char*, const std::string*>> outputs);
// Flushes `out` (if any); OutputError naming `path` if not everything was written.
void finish_output(std::ofstream* out, const std::string& path);

}  // namespace chainbench
