// SPDX-License-Identifier: MIT
// Running the chainbench command from a test: its exit status and what it printed. Shared by the
// cli_tests sources (cli_test.cpp, cli_faults_test.cpp, cli_refused_test.cpp).
#pragma once

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace cli {

struct Result {
  int status;       // the exit status, or -1 when the command did not exit (a signal)
  std::string out;  // what it printed on the streams the command line sends to the pipe
};

inline Result run_command(const std::string& cmd) {
  FILE* pipe = popen(cmd.c_str(), "r");
  if (!pipe) return {-1, "popen failed"};
  Result r{0, {}};
  std::array<char, 4096> buf;
  while (std::fgets(buf.data(), buf.size(), pipe))
    r.out += buf.data();
  const int raw = pclose(pipe);
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  return r;
}

// chainbench ARGS, stdout and stderr together.
inline Result chainbench(const std::string& args) {
  return run_command(std::string(CHAINBENCH_EXE) + " " + args + " 2>&1");
}

}  // namespace cli
