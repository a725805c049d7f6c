// SPDX-License-Identifier: MIT
// A progress line on stderr, drawn only when stderr is a terminal (never in logs or CI output).
#pragma once

#include <string>

namespace chainbench {

class Progress {
 public:
  Progress();
  ~Progress() { clear(); }
  // "label  done/total" with a bar, redrawn in place.
  void update(const std::string& label, long long done, long long total);
  void clear();
  bool enabled() const { return enabled_; }

 private:
  bool enabled_;
  bool drawn_ = false;
};

}  // namespace chainbench
