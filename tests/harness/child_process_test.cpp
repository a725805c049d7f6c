// SPDX-License-Identifier: MIT
// Work in a child process: its result comes back, and its death or its hang is an outcome.
#include "support/child_process.h"
#include "campaign/stress.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <csignal>
#include <thread>

namespace chainbench {
namespace {

struct Pair {
  int a;
  double b;
};

TEST(ChildProcess, ResultComesBackWhenTheChildFinishes) {
  Pair got{0, 0.0};
  const ChildOutcome o = run_in_child([] { return Pair{42, 2.5}; }, got, 60);
  EXPECT_TRUE(o.finished);
  EXPECT_FALSE(o.hang);
  EXPECT_EQ(got.a, 42);
  EXPECT_EQ(got.b, 2.5);
}

// SIGKILL rather than a segfault: the sanitizers turn a segfault into an exit of their own.
TEST(ChildProcess, ASignalEndsTheChildNotTheCaller) {
  Pair got{7, 7.0};
  const ChildOutcome o = run_in_child(
      [] {
        std::raise(SIGKILL);
        return Pair{1, 1.0};
      },
      got, 60);
  EXPECT_FALSE(o.finished);
  EXPECT_EQ(o.signal, SIGKILL);
  EXPECT_EQ(got.a, 7) << "a child that died must not write the caller's result";
}

TEST(ChildProcess, AnExitWithoutAResultIsReportedWithItsStatus) {
  Pair got{};
  const ChildOutcome o = run_in_child([]() -> Pair { _exit(5); }, got, 60);
  EXPECT_FALSE(o.finished);
  EXPECT_EQ(o.signal, 0);
  EXPECT_EQ(o.exit_status, 5);
}

TEST(ChildProcess, ChildOverItsTimeIsKilledAsAHang) {
  Pair got{};
  const ChildOutcome o = run_in_child(
      [] {
        std::this_thread::sleep_for(std::chrono::seconds(30));
        return Pair{};
      },
      got, 0.05);
  EXPECT_TRUE(o.hang);
  EXPECT_FALSE(o.finished);
  EXPECT_LT(o.wall_s, 20.0) << "the child must be killed, not waited for";
}

TEST(StressVerdicts, DeadChildIsACrashAndFatal) {
  StressVerdict killed;
  killed.engine = parse_engine_spec("chain");
  killed.signal = SIGSEGV;
  EXPECT_EQ(killed.verdict(), VerdictClass::kCrash);
  EXPECT_EQ(killed.verdict_detail(), "died of signal " + std::to_string(SIGSEGV));
  EXPECT_TRUE(killed.fatal());
  StressVerdict exited;
  exited.engine = parse_engine_spec("chain");
  exited.exit_status = 1;
  EXPECT_EQ(exited.verdict(), VerdictClass::kCrash);
  EXPECT_EQ(exited.verdict_detail(), "exited with status 1 and no result");
  EXPECT_TRUE(exited.fatal());
}

}  // namespace
}  // namespace chainbench
