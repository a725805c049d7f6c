// SPDX-License-Identifier: MIT
// Work in a child process (bench/support/child_process.h) against a child, or a plugin in it,
// that fights back: a result pipe closed early or held open by a process the child left behind,
// descriptors of the caller's files within reach, memory without end, and a plugin whose step
// fails (an error row, not the end of the run), or that dies while it is loaded.
#include "engines/registry.h"
#include "run/runner.h"
#include "support/child_process.h"
#include "support/input_error.h"

#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <string>

namespace chainbench {
namespace {

std::string plugin_spec(const std::string& fault) {
  return "plugin:path=" CHAINBENCH_TEST_PLUGINS "/libtest_plugin_" + fault + ".so";
}

Scene fall() {
  Scene s;
  s.name = "fall";
  s.steps = 20;
  s.bodies.push_back({"ball", BodyKind::kDynamic, {0, 10}, {0.5, 0.5}, {0, 0}, 1.0, 1.0, {}, {}});
  return s;
}

// A child that closes every descriptor (its result pipe too) and then never ends is a hang at
// its deadline: the pipe's end is not the child's.
TEST(Isolated, AChildThatClosesItsPipeIsStillTimed) {
  std::string bytes;
  const ChildOutcome o = run_in_child_bytes(
      []() -> std::string {
        for (int fd = 3; fd < 1024; ++fd)
          close(fd);
        for (;;)
          pause();
      },
      bytes, 1.0);
  EXPECT_TRUE(o.hang);
  EXPECT_LT(o.wall_s, 10.0);  // one second and the kill; ten for a loaded machine
}

// A child that leaves a process holding its pipe open and then crashes is a crash, found when
// the child ends, with no time limit at all.
TEST(Isolated, AChildThatDiesIsJudgedByItsExitWhateverHoldsItsPipe) {
  std::string bytes;
  const ChildOutcome o = run_in_child_bytes(
      []() -> std::string {
        if (fork() == 0) {
          close(0), close(1), close(2);
          setsid();  // out of the child's group: the kill of the group does not reach it
          sleep(20);
          _exit(0);
        }
        raise(SIGSEGV);
        return "";
      },
      bytes, HUGE_VAL);
  EXPECT_FALSE(o.hang);
  // A sanitizer reports the fault itself and ends the child with SIGABRT.
  EXPECT_EQ(o.signal, under_sanitizer() ? SIGABRT : SIGSEGV);
  EXPECT_LT(o.wall_s, 10.0);
}

// Dead or gone: no /proc entry, or a zombie's.
bool ended(pid_t pid) {
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string line;
  if (!std::getline(stat, line)) return true;
  const std::size_t paren = line.rfind(')');
  return paren != std::string::npos && paren + 2 < line.size() && line[paren + 2] == 'Z';
}

// A process the child started in its group goes with it when the time is up.
TEST(Isolated, ATimeoutKillsTheChildsWholeGroup) {
  std::string bytes;
  const ChildOutcome o = run_in_child_bytes(
      []() -> std::string {
        const pid_t grandchild = fork();
        if (grandchild == 0) {
          for (;;)
            pause();
        }
        child_mark()->store(grandchild);
        for (;;)
          pause();
      },
      bytes, 0.5);
  EXPECT_TRUE(o.hang);
  ASSERT_GT(o.mark, 0);
  bool gone = false;
  for (int k = 0; k < 200 && !gone; ++k) {
    gone = ended(o.mark);
    if (!gone) usleep(10000);
  }
  EXPECT_TRUE(gone) << "process " << o.mark << " outlived the timeout";
}

// The child reaches none of the caller's descriptors but the standard streams.
TEST(Isolated, TheChildInheritsNoDescriptorButStdio) {
  const int file = open("/dev/null", O_WRONLY);
  ASSERT_GT(file, 2);
  int open_in_child = -1;
  const ChildOutcome o = run_in_child(
      [&] {
        int n = 0;
        for (int fd = 3; fd < 1024; ++fd)
          n += fcntl(fd, F_GETFD) != -1 && fd == file;
        return n;
      },
      open_in_child, 60);
  close(file);
  ASSERT_TRUE(o.finished);
  EXPECT_EQ(open_in_child, 0);
}

// Its stdin is empty: a read of the terminal from outside its process group would stop it.
TEST(Isolated, TheChildReadsNothingFromStdin) {
  long got = -1;
  const ChildOutcome o = run_in_child(
      [] {
        char c;
        return static_cast<long>(read(0, &c, 1));
      },
      got, 60);
  ASSERT_TRUE(o.finished);
  EXPECT_EQ(got, 0);
}

// Memory without end meets the child's cap: a failure that says so, not a hang or a swapped-out
// machine.
TEST(Isolated, AChildOutOfMemoryIsSaid) {
  setenv("CHAINBENCH_CHILD_MEMORY_MB", "256", 1);
  const std::uint64_t cap = child_memory_cap();
  if (cap == 0) {
    unsetenv("CHAINBENCH_CHILD_MEMORY_MB");
    GTEST_SKIP() << "no cap under the sanitizers";
  }
  EXPECT_EQ(cap, std::uint64_t{256} << 20);
  std::string bytes;
  const ChildOutcome o = run_in_child_bytes(
      []() -> std::string {
        for (;;) {
          char* p = static_cast<char*>(std::malloc(1 << 24));
          if (!p) std::abort();
          for (int k = 0; k < (1 << 24); k += 4096)
            p[k] = 1;
        }
      },
      bytes, 60);
  unsetenv("CHAINBENCH_CHILD_MEMORY_MB");
  EXPECT_EQ(o.signal, SIGABRT);
  EXPECT_TRUE(o.out_of_memory);
  EXPECT_NE(child_failure(o, 60).find("out of memory (its cap is 256 MiB"), std::string::npos)
      << child_failure(o, 60);
}

// A plugin that dies in a run says at which step.
TEST(Isolated, ACrashSaysItsStep) {
  RunOptions child;
  child.isolate = true;
  child.timeout_s = 60;
  const EngineRun r = run_engine(fall(), parse_engine_spec(plugin_spec("crash")), child);
  ASSERT_TRUE(r.failure);
  EXPECT_NE(r.failure->find("at step 2"), std::string::npos) << *r.failure;
  EXPECT_EQ(r.verdict->worst, VerdictClass::kCrash);
}

// A step the plugin fails, or returns outside the contract, or a NaN it hands back, is the
// run's error row with the plugin's message, as in stress.
TEST(Isolated, AStepErrorIsTheRunsErrorRow) {
  RunOptions child;
  child.isolate = true;
  child.timeout_s = 60;
  for (const auto& [fault, why] : {std::pair{"step", "step 3 failed: the solver diverged"},
                                   std::pair{"step_rc", "step 3 returned 2"},
                                   std::pair{"nan", "returned a non-finite state for body ball"},
                                   std::pair{"counter_nan", "counter steps_so_far is NaN"}}) {
    SCOPED_TRACE(fault);
    const EngineRun r = run_engine(fall(), parse_engine_spec(plugin_spec(fault)), child);
    ASSERT_TRUE(r.failure);
    EXPECT_NE(r.failure->find(why), std::string::npos) << *r.failure;
    ASSERT_TRUE(r.verdict);
    EXPECT_EQ(r.verdict->worst, VerdictClass::kError);
  }
}

}  // namespace
}  // namespace chainbench
