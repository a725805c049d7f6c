// Work run in a forked child with a time limit: a crash, an abnormal exit or a hang in it becomes
// an outcome the caller reports, instead of the end of the caller.
#pragma once

#include <cstddef>
#include <functional>
#include <type_traits>

namespace chainbench {

struct ChildOutcome {
  bool finished = false;  // the child returned and its whole result arrived
  bool hang = false;      // killed after the time limit
  int signal = 0;         // the signal that ended the child, if one did
  int exit_status = 0;    // the child's exit status, if it exited without a full result
  double wall_s = 0.0;
};

// Runs `work` in a child process; `work` fills `size` bytes at `result`, which are copied back
// into the caller's `result` when the child finishes within `timeout_s` seconds.
ChildOutcome run_in_child(const std::function<void(void* result)>& work, void* result,
                          std::size_t size, double timeout_s);

// The same for a trivially copyable result returned by `work()`.
template <class T, class Work>
ChildOutcome run_in_child(Work&& work, T& result, double timeout_s) {
  static_assert(std::is_trivially_copyable_v<T>, "the result crosses a pipe as bytes");
  return run_in_child([&](void* out) { *static_cast<T*>(out) = work(); }, &result, sizeof(T),
                      timeout_s);
}

}  // namespace chainbench
