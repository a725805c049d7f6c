// SPDX-License-Identifier: MIT
// Work run in a forked child with a time limit: a crash, an abnormal exit or a hang in it becomes
// an outcome the caller reports, instead of the end of the caller.
#pragma once

#include <atomic>
#include <cstdint>
#include <cstring>
#include <functional>
#include <string>
#include <type_traits>

namespace chainbench {

struct ChildOutcome {
  bool finished = false;         // the child returned and its whole result arrived
  bool hang = false;             // killed after the time limit
  bool interrupted = false;      // killed because the caller's stop flag was set (Ctrl-C)
  int signal = 0;                // the signal that ended the child, if one did
  int exit_status = 0;           // the child's exit status, if it exited without a full result
  bool out_of_memory = false;    // it died near its memory cap
  std::uint64_t memory_cap = 0;  // that cap, bytes (child_memory_cap() when it started), or 0
  int mark = -1;                 // the last value the child stored in child_mark(), or -1
  double wall_s = 0.0;
};

// Runs `work` in a child process; the bytes it returns (any number) arrive in `result` when the
// child finishes within `timeout_s` seconds. The child is killed, with its whole process group
// (it leads one of its own), when the time is up, or when `stop` (if given) is set; SIGINT,
// SIGTERM and SIGHUP have their default effect in it. Guarantees:
// - the wait is bounded by the deadline and, without one, ends when the child ends: the result
//   pipe's state decides nothing (a child may close it early, or a process it started may hold
//   it open), and a child that ended is judged by its exit status;
// - before `work` runs, the child closes every descriptor it inherited except stdin, stdout,
//   stderr and its result pipe, so that it can never write into the caller's files, and reads
//   its stdin from /dev/null (out of the terminal's process group, a read would stop it);
// - the child's address space is capped at child_memory_cap() bytes (RLIMIT_AS).
ChildOutcome run_in_child_bytes(const std::function<std::string()>& work, std::string& result,
                                double timeout_s, const std::atomic<bool>* stop = nullptr);

// The memory cap of a child: CHAINBENCH_CHILD_MEMORY_MB mebibytes when that is set to a whole
// number above 0, else half the machine's physical memory, at least 2 GiB; 0 (no cap) in a build
// under AddressSanitizer or ThreadSanitizer, which reserve far more address space.
std::uint64_t child_memory_cap();

// Whether this build runs under a sanitizer (ASan, TSan, MSan): then a child that faults is
// reported by the sanitizer, which ends it with SIGABRT, not the signal of the fault.
bool under_sanitizer();

// In a child of run_in_child_bytes, a number shared with the parent (ChildOutcome::mark): the
// step a run has reached, say, so that a crash can say where. Null outside such a child.
std::atomic<int>* child_mark();

// "signal 11 (SIGSEGV)": a signal by number and name, as every message about a child gives it.
std::string signal_text(int signal);

// A human-readable reason for an outcome that did not finish, with `where` (" at step 3") after
// what happened: "died of signal 11 (SIGSEGV)",
// "ran out of time (60 s)", "exited with status 0 and no result", with ": out of memory (its cap is
// N MiB of address space)" when it ended near its cap.
std::string child_failure(const ChildOutcome& outcome, double timeout_s,
                          const std::string& where = "");

// The same for a trivially copyable result returned by `work()`.
template <class T, class Work>
ChildOutcome run_in_child(Work&& work, T& result, double timeout_s,
                          const std::atomic<bool>* stop = nullptr) {
  static_assert(std::is_trivially_copyable_v<T>, "the result crosses a pipe as bytes");
  std::string bytes;
  ChildOutcome o = run_in_child_bytes(
      [&] {
        const T value = work();
        return std::string(reinterpret_cast<const char*>(&value), sizeof(T));
      },
      bytes, timeout_s, stop);
  if (o.finished && bytes.size() == sizeof(T)) {
    std::memcpy(&result, bytes.data(), sizeof(T));
  } else {
    o.finished = false;
  }
  return o;
}

}  // namespace chainbench
