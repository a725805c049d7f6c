// SPDX-License-Identifier: MIT
// Ctrl-C while a command measures: the command stops after the work under way, keeps what
// finished, writes it and exits 130. While an Interrupt lives, SIGINT sets its flag instead of
// ending the process; the handler before it (output_file.h's, which removes temporaries) comes
// back when it goes.
#pragma once

#include <atomic>

namespace chainbench {

class Interrupt {
 public:
  Interrupt();
  ~Interrupt();
  Interrupt(const Interrupt&) = delete;
  Interrupt& operator=(const Interrupt&) = delete;

  const std::atomic<bool>* flag() const;  // for RunOptions::stop and its kin
  bool stopped() const { return flag()->load(); }
  // Prints "chainbench: interrupted; <what>" to standard error.
  static void report(const char* what);

 private:
  void (*previous_)(int);
};

inline constexpr int kInterruptedStatus = 130;  // as a shell reports a process ended by SIGINT

}  // namespace chainbench
