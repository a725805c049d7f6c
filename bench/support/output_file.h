// SPDX-License-Identifier: MIT
// The files a command writes (--json, --csv, --trace, --replay, merge's --json), each whole or
// not at all: the text goes to a temporary file beside the target, which commit_outputs() renames
// over it once everything is written. Until then the target keeps what it held (or stays
// absent); an output never committed (an error, Ctrl-C, SIGTERM, SIGHUP) removes its temporary.
// A target that exists and is not a regular file (a pipe), or is under /dev or /proc
// (/dev/stdout), is written directly; one that is the command's own standard output or error
// (/dev/stdout, wherever it is redirected) is written through that stream, in order with the
// rest of what the command prints.
#pragma once

#include <fstream>
#include <initializer_list>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace chainbench {

// An output file could not be written in full (a full disk, a device error), or standard output
// or standard error failed; exit status 1.
class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class OutputFile {
 public:
  // Creates the temporary beside `path`; InputError ("<option>: cannot write <path>: <why>") if
  // it cannot be created.
  OutputFile(const std::string& path, const char* option);
  ~OutputFile();  // removes the temporary unless committed
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  std::ostream& stream() { return out_; }
  // The bytes written so far, for cut_back(); -1 when the output is written directly.
  long long written();
  // Drops every byte written after the first `at` (a value of written()), so that what is written
  // next follows them: a trace keeps the engines that finished. False, and nothing dropped, when
  // the output is written directly (a pipe, a device): what went there cannot be taken back.
  bool cut_back(long long at);
  const std::string& path() const { return path_; }
  // std::cout or std::cerr when the target is the command's own standard output or error (what
  // it writes goes through that stream), else null.
  std::ostream* shared_stream() const { return shared_; }
  // Flushes and closes the temporary; OutputError naming the path if not everything was written.
  void finish();
  // Renames the finished temporary over the target; OutputError if the rename fails.
  void rename_into_place();

 private:
  std::string path_;    // as the user gave it, for messages
  std::string target_;  // what is replaced: the path with symbolic links followed
  std::string temp_;    // empty: written directly (a device or a pipe)
  int slot_ = -1;       // the temporary's place in the table the signal handler removes
  std::ofstream out_;   // its buffer is shared_'s when the target is the command's own stream
  std::ostream* shared_ = nullptr;  // std::cout or std::cerr, when the target is one of them
  bool finished_ = false, committed_ = false;
};

// The output at `path`, or null if `path` is empty.
std::unique_ptr<OutputFile> open_output(const std::string& path, const char* option);

// Finishes every output given (null ones are skipped) and only then renames them all into place:
// a full disk on the last leaves every target as it was.
void commit_outputs(std::initializer_list<OutputFile*> outputs);

// A named file a command reads or writes: (option, path); an empty path is not given.
using NamedFile = std::pair<const char*, const std::string*>;

// InputError (exit 2) if two outputs name the same file (the second would overwrite the first),
// or an output names one of the inputs (it would replace what the command reads). Files are
// compared by device and inode when they exist, so symbolic links, hard links and ./ paths are
// caught; by their absolute normal path otherwise.
void refuse_clashing_files(const std::vector<NamedFile>& outputs,
                           const std::vector<NamedFile>& inputs = {});

// OutputError ("cannot write standard output: <why>") if what was written to standard output or
// standard error did not all get there; flushes both first.
void check_standard_streams();

}  // namespace chainbench
