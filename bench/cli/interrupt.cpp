// SPDX-License-Identifier: MIT
#include "cli/interrupt.h"

#include <csignal>
#include <iostream>

namespace chainbench {
namespace {

std::atomic<bool> g_stop{false};

extern "C" void on_interrupt(int) {
  g_stop.store(true);
}

}  // namespace

Interrupt::Interrupt() {
  g_stop = false;
  previous_ = std::signal(SIGINT, on_interrupt);
}

Interrupt::~Interrupt() {
  std::signal(SIGINT, previous_);
}

const std::atomic<bool>* Interrupt::flag() const {
  return &g_stop;
}

void Interrupt::report(const char* what) {
  std::cerr << "chainbench: interrupted; " << what << '\n';
}

}  // namespace chainbench
