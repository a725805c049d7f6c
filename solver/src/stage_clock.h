// SPDX-License-Identifier: MIT
// Times the stages of a step for StepProfile: each lap adds the time since the last one to a
// stage. Off, it reads no clock, so a step that is not profiled pays a branch a stage.
#pragma once

#include <chrono>

namespace chain::detail {

class StageClock {
 public:
  using Clock = std::chrono::steady_clock;

  explicit StageClock(bool on) : on_(on) {
    if (on_) start_ = last_ = Clock::now();
  }
  // Adds the time since the previous lap (or the start) to `ms`, milliseconds.
  void lap(double& ms) {
    if (!on_) return;
    const Clock::time_point now = Clock::now();
    ms += std::chrono::duration<double, std::milli>(now - last_).count();
    last_ = now;
  }
  // Milliseconds since the start.
  double total() const {
    return on_ ? std::chrono::duration<double, std::milli>(Clock::now() - start_).count() : 0.0;
  }

 private:
  bool on_;
  Clock::time_point start_{}, last_{};
};

}  // namespace chain::detail
