// SPDX-License-Identifier: MIT
// The chainbench command under faults: outputs written whole or not at all, outputs that would
// replace an input, Ctrl-C, a standard output that cannot be written, and plugins that crash,
// abort, hang or exit in the middle of a run.
#include "cli_run.h"
#include "test_files.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace {

namespace fs = std::filesystem;

using cli::chainbench;
using cli::Result;

// A folder of this test's own, emptied.
std::string folder(const std::string& name) {
  return chainbench::test::fresh_folder("chainbench_faults_" + name);
}

void write(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

std::string plugin(const std::string& fault) {
  return std::string("plugin:path=") + CHAINBENCH_TEST_PLUGINS + "/libtest_plugin_" + fault + ".so";
}

// Files left in `dir` other than `keep`: temporaries a command forgot.
std::vector<std::string> leftovers(const std::string& dir, const std::vector<std::string>& keep) {
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (std::find(keep.begin(), keep.end(), name) == keep.end()) out.push_back(name);
  }
  return out;
}

// chainbench started in the background with `args`, its output into `log`; the hang plugin
// creates `mark` when its hang begins.
pid_t start(const std::vector<std::string>& args, const std::string& log, const std::string& mark) {
  const pid_t pid = fork();
  if (pid == 0) {
    setenv("CHAINBENCH_TEST_HANG_MARK", mark.c_str(), 1);
    const int fd = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(fd, 1);
    dup2(fd, 2);
    std::vector<char*> argv{const_cast<char*>(CHAINBENCH_EXE)};
    for (const std::string& a : args)
      argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execv(CHAINBENCH_EXE, argv.data());
    _exit(127);
  }
  return pid;
}

// Waits (up to 5 minutes, for slow sanitizer builds) for `path` to exist.
bool wait_for(const std::string& path) {
  for (int k = 0; k < 3000; ++k) {
    if (fs::exists(path)) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  return false;
}

// Whether some process still runs with `mark` in its environment (a child of a test's command).
bool runs_with(const std::string& mark) {
  const std::string entry = "CHAINBENCH_TEST_HANG_MARK=" + mark;
  for (const auto& e : fs::directory_iterator("/proc")) {
    const std::string environ = chainbench::test::read_file(e.path().string() + "/environ");
    if (environ.find(entry) != std::string::npos) return true;
  }
  return false;
}

// Waits (up to a minute) for every process with `mark` in its environment to end.
bool gone(const std::string& mark) {
  for (int k = 0; k < 600; ++k) {
    if (!runs_with(mark)) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  return false;
}

int finish(pid_t pid) {
  int raw = 0;
  waitpid(pid, &raw, 0);
  return WIFEXITED(raw) ? WEXITSTATUS(raw) : 128 + WTERMSIG(raw);
}

const std::string kScene = "--scene stack --set n=2 --set steps=60";

// A table sent to a full disk is a failure, not an exit 0 with nothing shown.
TEST(CliFaults, AStandardOutputThatCannotBeWrittenIsAnError) {
  const Result r = cli::run_command(std::string(CHAINBENCH_EXE) + " run " + kScene +
                                    " --engines chain --reference none 2>&1 >/dev/full");
  EXPECT_EQ(r.status, 1) << r.out;
  EXPECT_NE(r.out.find("cannot write standard output"), std::string::npos) << r.out;
}

// Killed while it runs, a command leaves the previous output as it was, and no temporary.
TEST(CliFaults, AKilledRunLeavesThePreviousOutputAndNoTemporary) {
  const std::string dir = folder("killed");
  write(dir + "out.json", "previous");
  const pid_t pid =
      start({"run", "--scene", "stack", "--set", "n=2", "--set", "steps=60", "--engines",
             plugin("hang"), "--reference", "none", "--json", dir + "out.json"},
            dir + "log", dir + "mark");
  ASSERT_TRUE(wait_for(dir + "mark"));
  kill(pid, SIGTERM);
  EXPECT_EQ(finish(pid), 128 + SIGTERM);
  EXPECT_EQ(chainbench::test::read_file(dir + "out.json"), "previous");
  EXPECT_EQ(leftovers(dir, {"out.json", "log", "mark"}), std::vector<std::string>{});
  EXPECT_TRUE(gone(dir + "mark")) << "the hung plugin's process outlived the command";
}

// Ctrl-C in run keeps the engines that finished, as sweep does.
TEST(CliFaults, CtrlCInRunKeepsTheEnginesThatFinished) {
  const std::string dir = folder("run_interrupt");
  write(dir + "out.json", "previous");
  const pid_t pid = start({"run", "--scene", "stack", "--set", "n=2", "--set", "steps=60",
                           "--engines", "chain," + plugin("hang"), "--reference", "none", "--json",
                           dir + "out.json", "--csv", dir + "out.csv"},
                          dir + "log", dir + "mark");
  ASSERT_TRUE(wait_for(dir + "mark"));
  kill(pid, SIGINT);
  EXPECT_EQ(finish(pid), 130) << chainbench::test::read_file(dir + "log");
  const nlohmann::json j = nlohmann::json::parse(chainbench::test::read_file(dir + "out.json"));
  EXPECT_TRUE(j["interrupted"].get<bool>());
  ASSERT_EQ(j["runs"].size(), 1u);
  EXPECT_EQ(j["runs"][0]["label"], "chain");
  EXPECT_NE(chainbench::test::read_file(dir + "out.csv").find("chain:variant=modern"),
            std::string::npos);
  EXPECT_NE(chainbench::test::read_file(dir + "log").find("interrupted"), std::string::npos);
  EXPECT_EQ(leftovers(dir, {"out.json", "out.csv", "log", "mark"}), std::vector<std::string>{});
}

// Ctrl-C in run writes only engines that finished: the trace holds none of the rows of the one
// cut short, and the replay page shows the finished ones and says it was interrupted.
TEST(CliFaults, CtrlCInRunWritesOnlyFinishedEnginesToTraceAndReplay) {
  const std::string dir = folder("run_interrupt_trace");
  const pid_t pid = start({"run", "--scene", "stack", "--set", "n=2", "--set", "steps=60",
                           "--engines", "chain," + plugin("hang"), "--reference", "none", "--trace",
                           dir + "t.csv", "--replay", dir + "r.html"},
                          dir + "log", dir + "mark");
  ASSERT_TRUE(wait_for(dir + "mark"));
  kill(pid, SIGINT);
  EXPECT_EQ(finish(pid), 130) << chainbench::test::read_file(dir + "log");
  std::istringstream trace(chainbench::test::read_file(dir + "t.csv"));
  std::string line;
  std::size_t rows = 0;
  std::getline(trace, line);  // the header
  while (std::getline(trace, line)) {
    if (line.empty() || line[0] == '#') continue;
    ++rows;
    EXPECT_EQ(line.rfind("chain,", 0), 0u) << line;
  }
  EXPECT_GT(rows, 0u);
  const std::string page = chainbench::test::read_file(dir + "r.html");
  EXPECT_NE(page.find("\"interrupted\":true"), std::string::npos);
  // The trace's metadata lists the engine that finished, and says the run was interrupted.
  const std::string meta = chainbench::test::read_file(dir + "t.csv.json");
  EXPECT_NE(meta.find("\"interrupted\": true"), std::string::npos) << meta;
  EXPECT_NE(meta.find("\"label\": \"chain\""), std::string::npos) << meta;
  EXPECT_EQ(meta.find("hang"), std::string::npos) << meta;
  EXPECT_EQ(leftovers(dir, {"t.csv", "t.csv.json", "r.html", "log", "mark"}),
            std::vector<std::string>{});
}

// Ctrl-C before anything finished leaves every previous output as it was (exit 130), in run,
// sweep and stress.
TEST(CliFaults, CtrlCBeforeAnythingFinishedLeavesThePreviousOutputs) {
  const std::string dir = folder("interrupt_nothing");
  const std::vector<std::string> outputs{"o.json", "o.csv", "o.trace", "o.html", "s.json"};
  for (const std::string& name : outputs)
    write(dir + name, "previous " + name);
  const pid_t run = start({"run", "--scene", "stack", "--set", "n=2", "--engines", plugin("hang"),
                           "--reference", "none", "--json", dir + "o.json", "--csv", dir + "o.csv",
                           "--trace", dir + "o.trace", "--replay", dir + "o.html"},
                          dir + "log", dir + "mark");
  ASSERT_TRUE(wait_for(dir + "mark"));
  kill(run, SIGINT);
  EXPECT_EQ(finish(run), 130) << chainbench::test::read_file(dir + "log");
  EXPECT_NE(chainbench::test::read_file(dir + "log")
                .find("no engine finished, so the outputs are left as they were"),
            std::string::npos)
      << chainbench::test::read_file(dir + "log");
  fs::remove(dir + "mark");
  const pid_t sweep =
      start({"sweep", "--scene", "stack", "--set", "n=2", "--set", "steps=60", "--grid",
             plugin("hang"), "--json", dir + "o.json", "--csv", dir + "o.csv"},
            dir + "log", dir + "mark");
  ASSERT_TRUE(wait_for(dir + "mark"));
  kill(sweep, SIGINT);
  EXPECT_EQ(finish(sweep), 130) << chainbench::test::read_file(dir + "log");
  fs::remove(dir + "mark");
  const pid_t stress = start({"stress", "--quick", "--filter", "size=0.01", "--engines",
                              plugin("hang"), "--json", dir + "s.json"},
                             dir + "log", dir + "mark");
  ASSERT_TRUE(wait_for(dir + "mark"));
  kill(stress, SIGINT);
  EXPECT_EQ(finish(stress), 130) << chainbench::test::read_file(dir + "log");
  for (const std::string& name : outputs)
    EXPECT_EQ(chainbench::test::read_file(dir + name), "previous " + name);
  std::vector<std::string> keep = outputs;
  keep.insert(keep.end(), {"log", "mark"});
  EXPECT_EQ(leftovers(dir, keep), std::vector<std::string>{});
}

// Ctrl-C in stress keeps the runs that finished.
TEST(CliFaults, CtrlCInStressKeepsTheRunsThatFinished) {
  const std::string dir = folder("stress_interrupt");
  const pid_t pid = start({"stress", "--quick", "--filter", "size=0.01", "--engines",
                           "chain," + plugin("hang"), "--json", dir + "s.json"},
                          dir + "log", dir + "mark");
  ASSERT_TRUE(wait_for(dir + "mark"));
  kill(pid, SIGINT);
  EXPECT_EQ(finish(pid), 130) << chainbench::test::read_file(dir + "log");
  const nlohmann::json j = nlohmann::json::parse(chainbench::test::read_file(dir + "s.json"));
  EXPECT_TRUE(j["interrupted"].get<bool>());
  ASSERT_EQ(j["cases"].size(), 1u);
  EXPECT_EQ(j["cases"][0]["label"], "chain");
}

// An output that names an input is refused before anything runs, however it is spelled.
TEST(CliFaults, AnOutputThatNamesAnInputIsRefused) {
  const std::string dir = folder("overwrite");
  const std::string scene = chainbench::test::read_file(std::string(CHAINBENCH_TEST_SCENES) +
                                                        "/verdicts/push_train.json");
  write(dir + "s.json", scene);
  fs::create_symlink(dir + "s.json", dir + "link.json");
  for (const std::string& out : {dir + "s.json", dir + "./s.json", dir + "link.json"}) {
    SCOPED_TRACE(out);
    const Result r = chainbench("run --scene-file " + dir + "s.json --engines chain --json " + out);
    EXPECT_EQ(r.status, 2) << r.out;
    EXPECT_NE(r.out.find("--json " + out + " is the input --scene-file " + dir + "s.json"),
              std::string::npos)
        << r.out;
    EXPECT_EQ(chainbench::test::read_file(dir + "s.json"), scene);
  }
  const Result sweep = chainbench("sweep --scene-file " + dir +
                                  "s.json --grid chain:passes=1 --csv " + dir + "link.json");
  EXPECT_EQ(sweep.status, 2) << sweep.out;
  EXPECT_EQ(chainbench::test::read_file(dir + "s.json"), scene);

  const std::string p1 = dir + "p1.json", p2 = dir + "p2.json";
  ASSERT_EQ(
      chainbench("sweep --scene stack --grid chain:passes=1,2 --shard 1/2 --json " + p1).status, 0);
  ASSERT_EQ(
      chainbench("sweep --scene stack --grid chain:passes=1,2 --shard 2/2 --json " + p2).status, 0);
  const std::string part = chainbench::test::read_file(p1);
  const Result merge = chainbench("merge " + p1 + " " + p2 + " --json " + p1);
  EXPECT_EQ(merge.status, 2) << merge.out;
  EXPECT_NE(merge.out.find("--json " + p1 + " is the input part " + p1), std::string::npos)
      << merge.out;
  EXPECT_EQ(chainbench::test::read_file(p1), part);
  EXPECT_EQ(chainbench("merge " + p1 + " " + p2 + " --json " + dir + "whole.json").status, 0);

  // A plugin's library is an input too: no output may replace it (here through a symlink).
  const std::string none = std::string(CHAINBENCH_TEST_PLUGINS) + "/libtest_plugin_none.so";
  const std::string lib = dir + "p.so", lib_link = dir + "p_link.so";
  fs::copy_file(none, lib);
  fs::create_symlink(lib, lib_link);
  const std::string library = chainbench::test::read_file(lib);
  for (const std::string& call :
       {"run --scene stack --reference none --engines chain,plugin:path=" + lib + " --json " +
            lib_link,
        "run --scene stack --reference none --engines chain,plugin:path=" + lib + " --csv " + lib,
        "sweep --scene stack --grid plugin:path=" + lib + " --grid chain --json " + lib_link,
        "stress --quick --engines plugin:path=" + lib + " --json " + lib}) {
    SCOPED_TRACE(call);
    const Result r = chainbench(call);
    EXPECT_EQ(r.status, 2) << r.out;
    EXPECT_NE(r.out.find("is the input --engines"), std::string::npos) << r.out;
    EXPECT_EQ(chainbench::test::read_file(lib), library);
  }
}

// A plugin that crashes, aborts, exits or hangs mid-run is that engine's crash or hang row; the
// other engines' results are kept and written, the run fails, and so does --require of it.
TEST(CliFaults, APluginThatDiesIsItsRowNotTheEndOfTheRun) {
  struct Case {
    const char* fault;
    const char* verdict;
    const char* reason;  // in the failure (a sanitizer may turn a signal into an exit)
    // The time limit: long enough for a sanitizer to report a crash, but for the hang.
    const char* timeout;
  };
  for (const Case& c : {Case{"crash", "crash", "", "60"}, Case{"abort", "crash", "", "60"},
                        Case{"exit", "crash", "exited with status 0 and no result", "60"},
                        Case{"hang", "hang", "ran out of time (1 s)", "1"}}) {
    SCOPED_TRACE(c.fault);
    const std::string dir = folder(std::string("dies_") + c.fault);
    write(dir + "out.json", "previous");
    const std::string engines = " --engines chain," + plugin(c.fault) + " --reference none";
    const Result r = chainbench("run " + kScene + engines + " --timeout " + c.timeout + " --json " +
                                dir + "out.json --csv " + dir + "out.csv");
    EXPECT_EQ(r.status, 1) << r.out;
    const nlohmann::json j = nlohmann::json::parse(chainbench::test::read_file(dir + "out.json"));
    ASSERT_EQ(j["runs"].size(), 2u);
    EXPECT_EQ(j["runs"][0]["label"], "chain");
    EXPECT_EQ(j["runs"][0]["final_positions"].size(), 3u);  // the ground and two boxes
    EXPECT_EQ(j["runs"][1]["verdict"]["class"], c.verdict);
    EXPECT_NE(j["runs"][1]["failure"].get<std::string>().find(c.reason), std::string::npos)
        << j["runs"][1];
    EXPECT_NE(r.out.find("libtest_plugin_" + std::string(c.fault) + ".so"), std::string::npos)
        << r.out;
    EXPECT_EQ(leftovers(dir, {"out.json", "out.csv"}), std::vector<std::string>{});

    const Result required = chainbench("run " + kScene + engines + " --timeout " + c.timeout +
                                       " --require " + plugin(c.fault));
    EXPECT_EQ(required.status, 3) << required.out;
    EXPECT_NE(required.out.find("fails: " + std::string(c.verdict)), std::string::npos)
        << required.out;

    const Result sweep =
        chainbench("sweep " + kScene + " --timeout " + c.timeout + " --grid chain:passes=1 " +
                   "--grid " + plugin(c.fault) + " --json " + dir + "sweep.json");
    EXPECT_EQ(sweep.status, 1) << sweep.out;
    const nlohmann::json s = nlohmann::json::parse(chainbench::test::read_file(dir + "sweep.json"));
    const auto& points = s["scenes"][0]["points"];
    ASSERT_EQ(points.size(), 2u) << s;
    EXPECT_EQ(points[0]["verdict"], "ok");
    EXPECT_EQ(points[1]["verdict"], c.verdict);
  }
}

// The reference runs beside the engines asked for, at a cost: a note says so, and how to skip it.
TEST(CliFaults, AReferenceNotAmongTheEnginesIsNoted) {
  const Result r = chainbench("run " + kScene + " --engines chain");
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("note: the reference box2d is not among --engines and runs too "
                       "(--reference none skips it)"),
            std::string::npos)
      << r.out;
  const Result none = chainbench("run " + kScene + " --engines chain --reference none");
  EXPECT_EQ(none.out.find("runs too"), std::string::npos) << none.out;
  const Result among = chainbench("run " + kScene + " --engines chain,box2d");
  EXPECT_EQ(among.out.find("runs too"), std::string::npos) << among.out;
}

// Fields of a CSV line as RFC 4180 reads them (quoted fields, quotes doubled), -1 when a quote is
// left open.
int csv_fields(const std::string& line) {
  int fields = 1;
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    if (line[i] == '"') {
      if (quoted && i + 1 < line.size() && line[i + 1] == '"') {
        ++i;
      } else {
        quoted = !quoted;
      }
    } else if (line[i] == ',' && !quoted) {
      ++fields;
    }
  }
  return quoted ? -1 : fields;
}

// A scene named with commas and quotes keeps every CSV row as wide as its header, in run and sweep.
TEST(CliFaults, NamesWithCommasAndQuotesKeepTheCsvColumns) {
  const std::string dir = folder("csv_names");
  nlohmann::json scene = nlohmann::json::parse(chainbench::test::read_file(
      std::string(CHAINBENCH_TEST_SCENES) + "/verdicts/push_train.json"));
  scene["name"] = "a\",b,c\"d";
  write(dir + "s.json", scene.dump());
  const std::string calls[] = {
      "run --scene-file " + dir + "s.json --engines chain --reference none --csv " + dir +
          "run.csv",
      "sweep --scene-file " + dir + "s.json --grid chain:passes=1,2 --csv " + dir + "sweep.csv"};
  for (const std::string& call : calls) {
    SCOPED_TRACE(call);
    ASSERT_EQ(chainbench(call).status, 0);
  }
  for (const std::string name : {"run.csv", "sweep.csv"}) {
    SCOPED_TRACE(name);
    std::istringstream csv(chainbench::test::read_file(dir + name));
    std::string header, row;
    ASSERT_TRUE(std::getline(csv, header));
    int rows = 0;
    while (std::getline(csv, row)) {
      if (row.empty() || row[0] == '#') continue;
      ++rows;
      EXPECT_EQ(csv_fields(row), csv_fields(header)) << row;
      EXPECT_EQ(row.rfind("\"a\"\",b,c\"\"d\",", 0), 0u) << row;
    }
    EXPECT_GT(rows, 0);
  }
}

}  // namespace
