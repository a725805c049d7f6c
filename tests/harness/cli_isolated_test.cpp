// SPDX-License-Identifier: MIT
// The chainbench command against plugins hostile to the process they run in: a result pipe
// closed early or held open by a process the plugin left behind, writes into the caller's
// descriptors, memory without end, a library that dies while it is loaded, and a step that fails.
#include "cli_run.h"
#include "support/child_process.h"
#include "test_files.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace {

namespace fs = std::filesystem;

// How a fault in a child is told: under a sanitizer, by its report and SIGABRT.
std::string segv_text() {
  return chainbench::under_sanitizer() ? "signal 6 (SIGABRT)" : "signal 11 (SIGSEGV)";
}

using cli::chainbench;
using cli::Result;
using Clock = std::chrono::steady_clock;

const std::string kScene = "--scene stack --set n=2 --set steps=60";

// A folder of this test's own, emptied.
std::string folder(const std::string& name) {
  return chainbench::test::fresh_folder("chainbench_isolated_" + name);
}

std::string plugin(const std::string& fault) {
  return std::string("plugin:path=") + CHAINBENCH_TEST_PLUGINS + "/libtest_plugin_" + fault + ".so";
}

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// --timeout holds when the plugin closed its result pipe; without --timeout a crash is found
// when the child ends, though a process it left behind holds the pipe open.
TEST(CliIsolated, TheWaitEndsWithTheChildOrItsTime) {
  const std::string engines = " --reference none --engines chain,";
  auto t0 = Clock::now();
  const Result closed =
      chainbench("run " + kScene + engines + plugin("close_fds") + " --timeout 1");
  EXPECT_LT(seconds_since(t0), 30.0);
  EXPECT_EQ(closed.status, 1) << closed.out;
  EXPECT_NE(closed.out.find("ran out of time (1 s) at step 3"), std::string::npos) << closed.out;

  t0 = Clock::now();
  const Result held = chainbench("run " + kScene + engines + plugin("fork_hold"));
  EXPECT_LT(seconds_since(t0), 15.0);  // its helper lives 20 s
  EXPECT_EQ(held.status, 1) << held.out;
  EXPECT_NE(held.out.find("died of " + segv_text() + " at step 3"), std::string::npos) << held.out;
  EXPECT_EQ(held.out.find("ran out of time"), std::string::npos) << held.out;
}

// A plugin writing into every descriptor it might have inherited reaches none of the outputs.
TEST(CliIsolated, APluginCannotWriteIntoAnOutput) {
  const std::string dir = folder("forge");
  const Result r = chainbench("run " + kScene + " --reference none --engines chain," +
                              plugin("forge") + " --json " + dir + "out.json --csv " + dir +
                              "out.csv --trace " + dir + "out.trace");
  EXPECT_EQ(r.status, 1) << r.out;
  const std::string json = chainbench::test::read_file(dir + "out.json");
  ASSERT_FALSE(json.empty());
  EXPECT_EQ(json.front(), '{');
  EXPECT_EQ(json.find("AAAA"), std::string::npos);
  EXPECT_TRUE(nlohmann::json::accept(json));
  EXPECT_EQ(chainbench::test::read_file(dir + "out.csv").find("AAAA"), std::string::npos);
  EXPECT_EQ(chainbench::test::read_file(dir + "out.trace").find("AAAA"), std::string::npos);
}

// Memory without end is that plugin's crash, said to be out of memory, not a hang. (Not under
// the sanitizers: there the child has no cap, child_process.h, and would take the machine; the
// command is built as this test is, so child_memory_cap() answers for it.)
TEST(CliIsolated, APluginOutOfMemoryIsSaid) {
  if (chainbench::child_memory_cap() == 0) GTEST_SKIP() << "no memory cap under the sanitizers";
  const Result r =
      cli::run_command("CHAINBENCH_CHILD_MEMORY_MB=256 " CHAINBENCH_EXE " run " + kScene +
                       " --reference none --engines chain," + plugin("oom") + " --timeout 60 2>&1");
  EXPECT_EQ(r.status, 1) << r.out;
  EXPECT_EQ(r.out.find("ran out of time"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("at step 3: out of memory (its cap is 256 MiB"), std::string::npos) << r.out;
}

// A library that dies while it is loaded and checked is refused by path in run, sweep and
// engines; in stress its cases are crash rows and the rest of the matrix goes on.
TEST(CliIsolated, APluginThatDiesWhileLoadingIsNamed) {
  for (const char* fault : {"load_crash", "entry_crash", "name_guard"}) {
    SCOPED_TRACE(fault);
    const std::string said =
        "libtest_plugin_" + std::string(fault) + ".so: crashed while loading: " + segv_text();
    for (const std::string& cmd :
         {"run " + kScene + " --engines chain," + plugin(fault),
          "sweep " + kScene + " --grid " + plugin(fault), "engines " + plugin(fault)}) {
      SCOPED_TRACE(cmd);
      const Result r = chainbench(cmd);
      EXPECT_EQ(r.status, 2) << r.out;
      EXPECT_NE(r.out.find(said), std::string::npos) << r.out;
    }
    const std::string dir = folder(std::string("load_") + fault);
    const Result r = chainbench("stress --quick --filter ledge_walk --engines chain," +
                                plugin(fault) + " --json " + dir + "stress.json");
    EXPECT_EQ(r.status, 1) << r.out;
    EXPECT_NE(r.out.find(said + " (its rows say crash"), std::string::npos) << r.out;
    const nlohmann::json j =
        nlohmann::json::parse(chainbench::test::read_file(dir + "stress.json"));
    ASSERT_EQ(j["cases"].size(), 2u) << j;
    EXPECT_NE(j["cases"][0]["verdict"], "crash") << j;
    EXPECT_EQ(j["cases"][1]["verdict"], "crash") << j;
  }
}

// A step error is the plugin's error row; the other engines' results are kept and written, and
// the command fails as for a crash (1), not as for bad input (2).
TEST(CliIsolated, AStepErrorIsAnErrorRowInRunAndSweep) {
  for (const char* fault : {"step", "step_rc", "nan", "counter_nan"}) {
    SCOPED_TRACE(fault);
    const std::string dir = folder(std::string("step_") + fault);
    const Result r = chainbench("run " + kScene + " --reference none --engines chain," +
                                plugin(fault) + " --json " + dir + "out.json");
    EXPECT_EQ(r.status, 1) << r.out;
    const nlohmann::json j = nlohmann::json::parse(chainbench::test::read_file(dir + "out.json"));
    ASSERT_EQ(j["runs"].size(), 2u);
    EXPECT_EQ(j["runs"][0]["final_positions"].size(), 3u);
    EXPECT_EQ(j["runs"][1]["verdict"]["class"], "error");

    const Result s = chainbench("sweep " + kScene + " --grid chain:passes=1 --grid " +
                                plugin(fault) + " --json " + dir + "sweep.json");
    EXPECT_EQ(s.status, 1) << s.out;
    const nlohmann::json sj =
        nlohmann::json::parse(chainbench::test::read_file(dir + "sweep.json"));
    const auto& points = sj["scenes"][0]["points"];
    ASSERT_EQ(points.size(), 2u) << sj;
    EXPECT_EQ(points[0]["verdict"], "ok");
    EXPECT_EQ(points[1]["verdict"], "error");
  }
}

// In stress too, a plugin that crashed, hung or failed a case fails the command (1), as in run and
// sweep, though the exit status otherwise judges only the engine that gates the build.
TEST(CliIsolated, APluginFaultInStressFailsTheCommand) {
  for (const auto& [fault, verdict] :
       {std::pair{"crash", "crash"}, std::pair{"step", "error"}, std::pair{"hang", "hang"}}) {
    SCOPED_TRACE(fault);
    const Result r = chainbench("stress --quick --filter ledge_walk --timeout 2 --engines chain," +
                                plugin(fault));
    EXPECT_EQ(r.status, 1) << r.out;
    EXPECT_NE(r.out.find(verdict), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("crashed, hung or failed on 1 stress case(s)"), std::string::npos)
        << r.out;
  }
}

}  // namespace
