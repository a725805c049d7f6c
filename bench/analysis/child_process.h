// Work run in a forked child with a time limit: a crash, an abnormal exit or a hang in it becomes
// an outcome the caller reports, instead of the end of the caller.
#pragma once

#include <atomic>
#include <cstring>
#include <functional>
#include <string>
#include <type_traits>

namespace chainbench {

struct ChildOutcome {
  bool finished = false;     // the child returned and its whole result arrived
  bool hang = false;         // killed after the time limit
  bool interrupted = false;  // killed because the caller's stop flag was set (Ctrl-C)
  int signal = 0;            // the signal that ended the child, if one did
  int exit_status = 0;       // the child's exit status, if it exited without a full result
  double wall_s = 0.0;
};

// Runs `work` in a child process; the bytes it returns (any number) arrive in `result` when the
// child finishes within `timeout_s` seconds. The child is killed when the time is up, or when
// `stop` (if given) is set; SIGINT, SIGTERM and SIGHUP have their default effect in it.
ChildOutcome run_in_child_bytes(const std::function<std::string()>& work, std::string& result,
                                double timeout_s, const std::atomic<bool>* stop = nullptr);

// A human-readable reason for an outcome that did not finish: "died of signal 11 (SIGSEGV)",
// "ran out of time (60 s)", "exited with status 0 and no result".
std::string child_failure(const ChildOutcome& outcome, double timeout_s);

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
