// SPDX-License-Identifier: MIT
// The chainbench command end to end: exit statuses, messages, and the JSON of `run`.
#include "cli_run.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <sys/wait.h>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

namespace {

using cli::chainbench;
using cli::Result;
using cli::run_command;

// The same with stdout and stderr a terminal (script(1)), as a user at one sees it.
Result chainbench_in_terminal(const std::string& args) {
  return run_command("script -qec '" + std::string(CHAINBENCH_EXE) + " " + args + "' /dev/null");
}

// The engines that run when none are named: chain, chain:variant=seed2014, box2d, chipmunk, and
// box2d3 when it is built (tests/CMakeLists.txt).
constexpr std::size_t kDefaultEngines = 4 + CHAINBENCH_BOX2D3_BUILT;

std::string temp(const std::string& name) {
  return ::testing::TempDir() + "chainbench_cli_" + name;
}

TEST(Cli, RunWritesTheDesignJsonAndNothingMovesAgainstAWall) {
  const std::string json_path = temp("wall.json");
  const Result r =
      chainbench("run --scene push_into_wall --set n=4 --set steps=60 --json " + json_path);
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("ms/step"), std::string::npos);
  EXPECT_NE(r.out.find("max ms"), std::string::npos) << r.out;
  nlohmann::json j;
  std::ifstream(json_path) >> j;
  EXPECT_EQ(j["schema"], "chainbench.run/1");
  EXPECT_EQ(j["scene"]["name"], "push_into_wall");
  EXPECT_EQ(j["scene"]["bodies"], 6);
  EXPECT_EQ(j["scene"]["steps"], 60);
  // chain, chain seed2014, box2d (the reference, among them), chipmunk, and box2d3 when built
  ASSERT_EQ(j["runs"].size(), kDefaultEngines);
  const double start[] = {0, 1, 2, 3, 4, 5};
  for (const auto& run : j["runs"]) {
    SCOPED_TRACE(run["engine"].get<std::string>());
    for (const char* key : {"engine", "final_positions", "ms_per_step", "metrics"})
      EXPECT_TRUE(run.contains(key)) << key;
    for (const char* key : {"median", "mean", "p95", "p99", "max"})
      EXPECT_TRUE(run["ms_per_step"].contains(key)) << key;
    // The worst frame is the slowest step: never below the quantiles under it.
    const auto& ms = run["ms_per_step"];
    EXPECT_GE(ms.value("median", -1.0), 0.0);
    EXPECT_GE(ms.value("p95", -1.0), ms.value("median", 0.0));
    EXPECT_GE(ms.value("p99", -1.0), ms.value("p95", 0.0));
    EXPECT_GE(ms.value("max", -1.0), ms.value("p99", 0.0));
    for (const char* key : {"energy_free_displacement", "max_penetration", "peak_speed", "finite",
                            "stable", "hash"}) {
      EXPECT_TRUE(run["metrics"].contains(key)) << key;
    }
    EXPECT_EQ(run["metrics"]["hash"].get<std::string>().size(), 16u);
    EXPECT_TRUE(run["metrics"]["stable"].get<bool>());
    const bool is_chain = run["engine"].get<std::string>().rfind("chain", 0) == 0;
    EXPECT_EQ(run.contains("chain_stats"), is_chain);
    EXPECT_TRUE(run.contains("counters"));
    // Chipmunk at its defaults lets the driven pusher sink 0.4 m into the row, which its verdict
    // reports; the others hold it.
    if (run["label"] == "chipmunk") {
      EXPECT_NE(run["verdict"]["class"], "ok");
      continue;
    }
    // Chain holds the row exactly; Box2D gives way by its contact softness, a few mm per contact.
    const double tolerance = is_chain ? 1e-9 : 0.03;
    ASSERT_EQ(run["final_positions"].size(), 6u);
    for (int i = 0; i < 5; ++i) {
      EXPECT_NEAR(run["final_positions"][i][0].get<double>(), start[i], tolerance) << "body " << i;
      EXPECT_NEAR(run["final_positions"][i][1].get<double>(), 0.0, tolerance) << "body " << i;
    }
  }
  ASSERT_EQ(j["comparison"].size(), kDefaultEngines - 1);
  EXPECT_EQ(j["comparison"][0]["reference"],
            "box2d:vel_iters=8,pos_iters=3,substeps=1,skin=compensate,warm=1,ccd=1,sleep=0");
  EXPECT_LT(j["comparison"][0]["final_position_error"]["max"].get<double>(), 0.03);
}

TEST(Cli, CsvAndTraceAreWritten) {
  std::filesystem::remove(temp("s.trace.csv") + ".json");
  const Result r =
      chainbench("run --scene squeeze --set steps=10 --engines chain --reference none --csv " +
                 temp("s.csv") + " --trace " + temp("s.trace.csv") + " --trace-format sparse");
  ASSERT_EQ(r.status, 0) << r.out;
  std::ifstream csv(temp("s.csv")), trace(temp("s.trace.csv"));
  std::string header, row;
  std::getline(csv, header);
  std::getline(csv, row);
  EXPECT_EQ(header.rfind("scene,engine,bodies,steps,dt,ms_median,ms_mean,ms_p95,ms_p99,ms_max,", 0),
            0u)
      << header;
  EXPECT_EQ(row.rfind("squeeze,\"chain:variant=modern", 0), 0u) << row;
  int comments = 0, lift = 0, others = 0;
  std::getline(trace, header);
  EXPECT_EQ(header, "engine,step,body,x,y,vx,vy,angle,displacement,penetration");
  for (std::string l; std::getline(trace, l);) {
    if (l.rfind('#', 0) == 0) {
      ++comments;
    } else {
      (l.find(",lift,") != std::string::npos ? lift : others)++;
    }
  }
  EXPECT_EQ(comments, 4);  // the format, dt, steps, the engine's spec
  // The lift descends every step; the ground and the box stay put and are written once.
  EXPECT_EQ(lift, 10);
  EXPECT_EQ(others, 2);
  EXPECT_FALSE(std::filesystem::exists(temp("s.trace.csv") + ".json"))
      << "the sparse form keeps its metadata in its comments";
}

// A sparse trace written over a dense one takes the dense one's metadata with it: left, it would
// describe another run. A FILE.json that is not a trace's metadata is left alone.
TEST(Cli, ASparseTraceOverADenseOneRemovesItsStaleMetadata) {
  const std::string path = temp("stale.trace.csv");
  ASSERT_EQ(
      chainbench("run --scene stack --steps 2 --engines chain --reference none --trace " + path)
          .status,
      0);
  ASSERT_TRUE(std::filesystem::exists(path + ".json"));
  const Result sparse = chainbench(
      "run --scene stack --steps 2 --engines chain --reference none "
      "--trace-format sparse --trace " +
      path);
  ASSERT_EQ(sparse.status, 0) << sparse.out;
  EXPECT_FALSE(std::filesystem::exists(path + ".json"));
  EXPECT_NE(sparse.out.find("removed " + path + ".json"), std::string::npos) << sparse.out;
  {
    std::ofstream other(path + ".json");
    other << "{\"mine\": true}\n";
  }
  ASSERT_EQ(chainbench("run --scene stack --steps 2 --engines chain --reference none "
                       "--trace-format sparse --trace " +
                       path)
                .status,
            0);
  EXPECT_TRUE(std::filesystem::exists(path + ".json")) << "a file of someone else's was removed";
  std::filesystem::remove(path + ".json");
}

// --trace /dev/stdout with standard output sent to a file: the rows and the table both arrive,
// in order (a second descriptor on the file would write the table over the rows).
TEST(Cli, ATraceToStandardOutputRedirectedToAFileKeepsEveryRow) {
  const std::string out = temp("stdout_trace.txt");
  const Result r = run_command(std::string(CHAINBENCH_EXE) +
                               " run --scene stack --steps 3 --engines chain --reference none "
                               "--trace /dev/stdout > " +
                               out + " 2>/dev/null");
  ASSERT_EQ(r.status, 0);
  std::ifstream in(out);
  std::string first;
  std::getline(in, first);
  EXPECT_EQ(first, "engine,step,time,body,x,y,vx,vy,angle,displacement,penetration");
  int rows = 0;
  bool table = false;
  for (std::string l; std::getline(in, l);) {
    if (l.rfind("chain,", 0) == 0) {
      EXPECT_FALSE(table) << "a row after the table";
      ++rows;
    }
    if (l.rfind("scene stack", 0) == 0) table = true;
  }
  EXPECT_EQ(rows, 3 * 16);  // three steps of the stack's 16 bodies
  EXPECT_TRUE(table);
}

// An output that is the file standard output is redirected to (by its own name) is written
// through standard output: the table and the JSON both arrive, neither over the other.
TEST(Cli, AnOutputThatIsStandardOutputsFileKeepsTheTableToo) {
  const std::string path = temp("same_as_stdout.txt");
  const Result r = run_command(std::string(CHAINBENCH_EXE) +
                               " run --scene stack --steps 2 --engines chain --reference none "
                               "--json " +
                               path + " > " + path + " 2>/dev/null");
  ASSERT_EQ(r.status, 0);
  std::ifstream in(path);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t json = text.find("{\n  \"schema\": \"chainbench.run/1\"");
  ASSERT_NE(json, std::string::npos) << text;
  EXPECT_NE(text.find("scene stack:"), std::string::npos) << text;
  const nlohmann::json parsed = nlohmann::json::parse(text.substr(json), nullptr, false);
  EXPECT_FALSE(parsed.is_discarded()) << text.substr(json);
}

// The dense trace (the default): a row per step and body, and its metadata in FILE.json.
TEST(Cli, TheDenseTraceHasEveryRowAndItsMetadataBesideIt) {
  const std::string path = temp("d.trace.csv");
  const Result r = chainbench(
      "run --scene squeeze --set steps=10 --engines chain,box2d "
      "--reference none --trace " +
      path);
  ASSERT_EQ(r.status, 0) << r.out;
  std::ifstream trace(path);
  std::string header;
  std::getline(trace, header);
  EXPECT_EQ(header, "engine,step,time,body,x,y,vx,vy,angle,displacement,penetration");
  int rows = 0;
  for (std::string l; std::getline(trace, l);) {
    ++rows;
    EXPECT_NE(l[0], '#') << l;
  }
  EXPECT_EQ(rows, 2 * 10 * 3);  // two engines, ten steps, three bodies
  std::ifstream meta_file(path + ".json");
  ASSERT_TRUE(meta_file) << "no " << path << ".json";
  const nlohmann::json meta = nlohmann::json::parse(meta_file);
  EXPECT_EQ(meta["schema"], "chainbench.trace/1");
  EXPECT_EQ(meta["scene"]["name"], "squeeze");
  EXPECT_EQ(meta["scene"]["steps"], 10);
  ASSERT_EQ(meta["engines"].size(), 2u);
  EXPECT_EQ(meta["engines"][0]["label"], "chain");
  EXPECT_EQ(meta["engines"][1]["label"], "box2d");
  EXPECT_EQ(meta["interrupted"], false);
  // The sidecar is an output like the others: it may not overwrite another.
  const Result clash =
      chainbench("run --scene squeeze --set steps=2 --trace " + path + " --json " + path + ".json");
  EXPECT_EQ(clash.status, 2);
  EXPECT_NE(clash.out.find("--trace's metadata both name"), std::string::npos) << clash.out;
}

// Large bad inputs are refused as small ones are (a message, exit 2), with what they echo cut
// to a readable length. (Their time, linear in the input, is measured outside the tests.)
TEST(Cli, LargeBadInputsAreRefusedWithShortMessages) {
  const std::string bodies = temp("bad_bodies.json");
  {
    std::ofstream f(bodies);
    f << R"({"name": "bad", "bodies": [)";
    for (int i = 0; i < 40000; ++i)
      f << (i ? "," : "") << R"({"center": [0, "x"]})";
    f << "]}";
  }
  Result r = chainbench("run --scene-file " + bodies);
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.out.find("more"), std::string::npos) << r.out.substr(0, 2000);
  EXPECT_LT(r.out.size(), 20000u);
  const std::string keys = temp("many_keys.json");
  {
    std::ofstream f(keys);
    f << R"({"name": "keys", "bodies": [], "x": {)";
    for (int i = 0; i < 80000; ++i)
      f << (i ? "," : "") << "\"k" << i << "\": 1";
    f << R"(, "k7": 2}})";
  }
  r = chainbench("run --scene-file " + keys);
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.out.find("x.k7: is given twice"), std::string::npos) << r.out.substr(0, 2000);
  std::string engines;
  for (int i = 1; i < 5000; ++i)
    engines += "chain:budget=" + std::to_string(i) + ",";
  engines += "chain:budget=1";
  r = chainbench("run --scene stack --engines '" + engines + "'");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.out.find("bytes)\": chain:budget=1 given twice"), std::string::npos)
      << r.out.substr(0, 2000);
  EXPECT_LT(r.out.size(), 1000u);
  // What --set echoes of a long key or value is cut as well.
  const std::string key(10000, 'k'), zeros(10000, '0');
  for (const std::string& set :
       {key + "=1", "n=1.5" + zeros, "n=" + zeros + "1 --set n=1", "n=1 --set n=" + zeros, key}) {
    r = chainbench("run --scene stack --set " + set);
    EXPECT_EQ(r.status, 2) << set.substr(0, 40);
    EXPECT_NE(r.out.find("bytes)"), std::string::npos) << r.out.substr(0, 2000);
    EXPECT_LT(r.out.size(), 1000u) << set.substr(0, 40);
  }
}

// The first step is left out of the timing as a warm-up, except when it is the only one: a run
// of one step is timed by it rather than reported as taking no time.
TEST(Cli, ARunOfOneStepIsTimedByThatStep) {
  const std::string json = temp("one_step.json");
  const Result r =
      chainbench("run --scene stack --steps 1 --engines chain --reference none --json " + json);
  ASSERT_EQ(r.status, 0) << r.out;
  std::ifstream in(json);
  const auto j = nlohmann::json::parse(in);
  const auto& timing = j.at("runs").at(0).at("ms_per_step");
  EXPECT_EQ(timing.at("samples").get<int>(), 1);
  EXPECT_GT(timing.at("median").get<double>(), 0.0);
}

// A scene file larger than any scene needs is refused before it is read (a sparse file here;
// a device with no end, /dev/zero, is refused once that much has been read).
TEST(Cli, ASceneFileLargerThanAnySceneNeedsIsRefused) {
  const std::string path = temp("huge_scene.json");
  { std::ofstream(path) << "{"; }
  std::filesystem::resize_file(path, 3'000'000'000ull);
  const Result r = chainbench("run --scene-file " + path);
  std::filesystem::remove(path);
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_NE(r.out.find(path + ": larger than 2 GB"), std::string::npos) << r.out;
}

// --steps takes a whole number in any form, as --set does: 1e1 is ten steps.
TEST(Cli, StepsTakesAWholeNumberWrittenInAnyForm) {
  for (const char* steps : {"1e1", "10.0", "10"}) {
    const Result r = chainbench(std::string("run --scene stack --engines chain --reference none "
                                            "--steps ") +
                                steps);
    EXPECT_EQ(r.status, 0) << steps << ": " << r.out;
  }
}

TEST(Cli, VersionIsPrinted) {
  const Result r = chainbench("--version");
  EXPECT_EQ(r.status, 0);
  EXPECT_EQ(r.out, std::string("chainbench ") + CHAINBENCH_VERSION + "\n");
}

// --require gates a build: exit 3 naming what the required engine missed, 0 when it meets every
// expectation with verdict ok.
TEST(Cli, RequireExitsThreeNamingWhatFailed) {
  const std::string train = std::string(CHAINBENCH_TEST_SCENES) + "/verdicts/push_train.json";
  const Result ok = chainbench("run --scene-file " + train + " --require chain");
  EXPECT_EQ(ok.status, 0) << ok.out;
  const Result missed =
      chainbench("run --scene-file " + train + " --engines chain,box2d --require box2d");
  EXPECT_EQ(missed.status, 3) << missed.out;
  EXPECT_NE(missed.out.find("required engine box2d fails: wrong: expect[0] moved b5"),
            std::string::npos)
      << missed.out;
  // Even with no metric asked for: the verdict needs stability and penetration, so they run.
  const Result bare =
      chainbench("run --scene-file " + train +
                 " --engines chain --reference none --metrics none --require chain");
  EXPECT_EQ(bare.status, 0) << bare.out;
}

// The run JSON names every body and lists every expectation with its actual value and verdict.
TEST(Cli, RunJsonNamesBodiesAndEveryExpectation) {
  const std::string train = std::string(CHAINBENCH_TEST_SCENES) + "/verdicts/push_train.json";
  const std::string json_path = temp("train.json");
  const Result r = chainbench("run --scene-file " + train + " --json " + json_path);
  ASSERT_EQ(r.status, 0) << r.out;
  nlohmann::json j;
  std::ifstream(json_path) >> j;
  EXPECT_EQ(j["scene"]["names"][5], "b5");
  EXPECT_EQ(j["scene"]["kinds"][0], "dynamic");
  EXPECT_EQ(j["scene"]["expect"][0]["kind"], "moved");
  EXPECT_EQ(j["scene"]["expect"][0]["body"], "*");
  for (const auto& run : j["runs"]) {
    SCOPED_TRACE(run["label"].get<std::string>());
    const auto& entry = run["expect"]["entries"][0];
    for (const char* key :
         {"kind", "body", "moved", "tolerance", "worst_body", "step", "actual", "error", "pass"}) {
      EXPECT_TRUE(entry.contains(key)) << key;
    }
    EXPECT_EQ(entry["step"], 150);
    EXPECT_TRUE(run["verdict"].contains("class"));
    EXPECT_TRUE(run["metrics"].contains("tunnelled"));
    EXPECT_TRUE(run["metrics"].contains("peak_speed_body"));
  }
  EXPECT_EQ(j["runs"][0]["verdict"]["class"], "ok");
}

// A scene file run for fewer steps than its own says which expectations it no longer checks.
TEST(Cli, ShorterRunOfASceneFileDropsItsFinalStateExpectations) {
  const std::string train = std::string(CHAINBENCH_TEST_SCENES) + "/verdicts/push_train.json";
  const Result r = chainbench("run --scene-file " + train + " --steps 50 --engines chain");
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("note: 1 expectation(s) of " + train +
                       " judge the state where bodies end, at step 150"),
            std::string::npos)
      << r.out;
}

TEST(Cli, BadSceneFileNamesFileAndPath) {
  const std::string path = temp("bad.json");
  std::ofstream(path)
      << R"({"bodies": [{"type": "dynamic", "center": [0, 0], "half_extents": [0.5, -1], "mass": 1}]})";
  const Result r = chainbench("run --scene-file " + path);
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_NE(r.out.find(path + ": bodies[0].half_extents[1]: must be > 0"), std::string::npos)
      << r.out;
}

// /dev/full opens but takes nothing: every command that writes a file says which one it could not
// finish, with status 1 and without calling it an internal error.
TEST(Cli, AnOutputFileThatCannotBeFinishedIsNamed) {
  for (const std::string call :
       {"run --scene stack --engines chain --json /dev/full",
        "run --scene stack --engines chain --trace /dev/full",
        "sweep --scene stack --csv /dev/full", "stress --quick --filter stack --json /dev/full"}) {
    const Result r = chainbench(call);
    EXPECT_EQ(r.status, 1) << call << '\n' << r.out;
    EXPECT_NE(r.out.find("could not finish writing /dev/full"), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("internal error"), std::string::npos) << r.out;
  }
}

// The progress line (drawn only on a terminal: `script` gives the run one) names each engine by
// the label the table uses, after the scene, not by its canonical spec.
TEST(Cli, TheProgressLineShowsLabels) {
  if (std::system("command -v script > /dev/null 2>&1") != 0) GTEST_SKIP() << "no script(1)";
  const Result r = chainbench_in_terminal(
      "run --scene push_row --set steps=400 --engines chain:velocity=zero --reference none "
      "--metrics none");
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("\rpush_row: chain:velocity=zero "), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("\rchain:variant="), std::string::npos) << r.out;
}

TEST(Cli, ListAndEnginesDescribeWhatCanRun) {
  const Result list = chainbench("list");
  EXPECT_EQ(list.status, 0);
  for (const char* scene :
       {"stack", "pyramid", "many_pyramids", "mass_ratio_stack", "heavy_on_light",
        "overlap_recovery", "push_row", "push_into_wall", "push_stack", "squeeze", "seed_stack",
        "seed_squeeze", "seed_falling_row"}) {
    EXPECT_NE(list.out.find(std::string("  ") + scene + ": "), std::string::npos) << scene;
  }
  // Ranges in full: a rounded bound would look equal to a value just past it.
  EXPECT_NE(list.out.find("[0, 2147483647] whole"), std::string::npos) << list.out;
  EXPECT_NE(list.out.find("[1, 10000000] whole"), std::string::npos) << list.out;
  EXPECT_EQ(list.out.find("e+0"), std::string::npos) << list.out;
  // Every key --set accepts is listed under each scene, those every scene takes included.
  std::istringstream lines(list.out.substr(list.out.find("\n  stack: ") + 1));
  std::string line, stack_keys;
  std::getline(lines, line);  // the scene's own line; its key table follows, to the next scene's
  while (std::getline(lines, line) &&
         !(line.size() > 2 && line.rfind("  ", 0) == 0 && line[2] != ' '))
    stack_keys += line + "\n";
  for (const char* key : {"steps", "dt", "friction", "restitution", "rotation", "offset"})
    EXPECT_NE(stack_keys.find(std::string("    ") + key + " "), std::string::npos) << key;
  const Result engines = chainbench("engines");
  // Limits an engine imposes whatever the scene asks.
  EXPECT_NE(engines.out.find("  limit: moves no body more than this in one world step "
                             "(b2_maxTranslation): 2 m"),
            std::string::npos)
      << engines.out;
  EXPECT_EQ(engines.status, 0);
  EXPECT_NE(engines.out.find("chain:variant=modern,velocity=inelastic"), std::string::npos)
      << engines.out;
  for (const char* engine : {"box2d", "chipmunk", "plugin"}) {
    EXPECT_NE(engines.out.find(engine), std::string::npos) << engine;
  }
  EXPECT_NE(engines.out.find("vel_iters"), std::string::npos);
  EXPECT_EQ(chainbench("--help").status, 0);
  EXPECT_EQ(chainbench("-h").status, 0);
  EXPECT_EQ(chainbench("--help-all").status, 0);
  // A command's --help-all says that it prints that command's help only.
  const Result run_help = chainbench("run --help");
  EXPECT_NE(run_help.out.find("this command's help, as --help"), std::string::npos) << run_help.out;
  const Result run_all = chainbench("run --help-all");
  EXPECT_EQ(run_all.status, 0);
  EXPECT_NE(run_all.out.find("--scene-file"), std::string::npos) << run_all.out;
}

// The example scene files load, run in every default engine, and the modern solver lands where
// each file expects (push_two: the pusher's speed carries the row; corridor: the crates end
// against the wall; lift: two boxes ride a lift up).
TEST(Cli, ExampleSceneFilesRunAndModernChainingMeetsTheirExpectations) {
  for (const char* name : {"push_two", "corridor", "lift"}) {
    SCOPED_TRACE(name);
    const std::string json_path = temp(std::string(name) + ".json");
    const Result r = chainbench(std::string("run --scene-file ") + CHAINBENCH_EXAMPLES + "/" +
                                name + ".json --json " + json_path);
    ASSERT_EQ(r.status, 0) << r.out;
    nlohmann::json j;
    std::ifstream(json_path) >> j;
    ASSERT_EQ(j["runs"].size(), kDefaultEngines);
    for (const auto& run : j["runs"])
      EXPECT_TRUE(run["metrics"]["stable"].get<bool>());
    const auto& modern = j["runs"][0];
    ASSERT_EQ(modern["label"], "chain");
    ASSERT_TRUE(modern.contains("expect"));
    EXPECT_TRUE(modern["expect"]["pass"].get<bool>()) << modern["expect"];
  }
}

TEST(Cli, QuickStressWritesAVerdictForEveryCaseAndEngine) {
  const std::string json_path = temp("stress.json");
  const Result r =
      chainbench("stress --quick --filter \"projectile|static_squeeze\" --json " + json_path);
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("verdict"), std::string::npos);
  nlohmann::json j;
  std::ifstream(json_path) >> j;
  EXPECT_EQ(j["schema"], "chainbench.stress/1");
  EXPECT_TRUE(j["quick"].get<bool>());
  ASSERT_EQ(j["cases"].size(), 2u * kDefaultEngines);  // two cases, every default engine
  for (const auto& c : j["cases"]) {
    SCOPED_TRACE(c["case"].get<std::string>() + " " + c["engine"].get<std::string>());
    for (const char* key :
         {"case", "group", "engine", "label", "verdict", "detail", "stable", "fatal", "finite",
          "in_bounds", "blow_up", "tunnelled", "expect_pass", "budget_hits", "crush_events",
          "max_penetration", "ms_per_step", "wall_s"}) {
      EXPECT_TRUE(c.contains(key)) << key;
    }
    // The modern solver is right on both: the projectile stops against box2, the squeezed box
    // stays between floor and ceiling.
    if (c["label"] == "chain") {
      EXPECT_EQ(c["verdict"], "ok") << c["detail"];
      EXPECT_FALSE(c["fatal"].get<bool>());
    }
  }
  // The box between floor and ceiling is crushed every step, which the chain engines count.
  const auto& squeezed = j["cases"][kDefaultEngines];  // the second case's first engine
  ASSERT_EQ(squeezed["label"], "chain");
  EXPECT_GT(squeezed["crush_events"].get<int>(), 0) << squeezed["case"];
  // The table prints every class it met, and what each rests on.
  EXPECT_NE(r.out.find("runs:"), std::string::npos) << r.out;
}

// The page of a run has its engines in the order given even though the reference runs first,
// measures every other engine from it, and without a reference charts no distance from one.
TEST(Cli, RunWritesAReplayPageOfItsEngines) {
  const std::string page = temp("replay.html");
  Result r = chainbench(
      "run --scene push_row --set n=2 --steps 20 --engines chain,box2d --replay " + page);
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_LT(r.out.find("chain  "), r.out.find("box2d (ref)")) << r.out;
  EXPECT_NE(r.out.find("replay: wrote " + page), std::string::npos) << r.out;
  auto data = [&] {
    std::ifstream in(page);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::string open = "id=\"replay-data\">";
    const std::size_t from = text.find(open) + open.size();
    return nlohmann::json::parse(text.substr(from, text.find("</script>", from) - from));
  };
  nlohmann::json j = data();
  ASSERT_EQ(j["engines"].size(), 2u);
  EXPECT_EQ(j["engines"][0]["label"], "chain");
  EXPECT_EQ(j["reference"], 1);
  EXPECT_EQ(j["engines"][0]["series"]["error_max"].size(), 21u);
  EXPECT_GT(j["engines"][0]["series"]["error_max"][20].get<double>(), 0.0);

  r = chainbench(
      "run --scene push_row --set n=2 --steps 20 --engines chain --reference none "
      "--replay " +
      page);
  ASSERT_EQ(r.status, 0) << r.out;
  j = data();
  EXPECT_TRUE(j["reference"].is_null());
  EXPECT_FALSE(j["engines"][0]["series"].contains("error_max"));
  EXPECT_EQ(j["engines"][0]["series"]["efd"].size(), 21u);
}

// A page that cannot fit its size limit even with only its first and last states is refused,
// naming the size it needs, and leaves no file; one that fits keeps within the limit.
TEST(Cli, AReplayPageKeepsItsSizeLimitOrIsRefused) {
  const std::string page = temp("limit.html");
  std::remove(page.c_str());
  Result r = chainbench(
      "replay --scene pyramid --set base=60 --engines chain,box2d --replay-mb 0.1 --out " + page);
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_NE(r.out.find("needs at least"), std::string::npos) << r.out;
  // One name for the limit, as `run --replay-mb` has it; the old --max-mb is still read.
  EXPECT_NE(r.out.find("more than --replay-mb 0.1 allows"), std::string::npos) << r.out;
  EXPECT_FALSE(std::ifstream(page).good());
  r = chainbench("replay --scene pyramid --set base=60 --engines chain,box2d --max-mb 0.5 --out " +
                 page);
  ASSERT_EQ(r.status, 0) << r.out;
  std::ifstream in(page, std::ios::binary | std::ios::ate);
  EXPECT_LE(static_cast<double>(in.tellg()), 0.5e6);
}

}  // namespace

namespace {

const std::string kRelaxation = std::string("plugin:path=") + CHAINBENCH_RELAXATION_PLUGIN;

// A plugin runs in every command like a built-in engine, labelled by its library's name, with
// its counters in the JSON.
TEST(Cli, APluginRunsInRunSweepAndStress) {
  const std::string run_json = temp("plugin_run.json");
  const Result run = chainbench("run --scene stack --set n=3 --engines chain," + kRelaxation +
                                ",iterations=8 --json " + run_json);
  ASSERT_EQ(run.status, 0) << run.out;
  nlohmann::json j;
  std::ifstream(run_json) >> j;
  ASSERT_EQ(j["runs"].size(), 2u);
  EXPECT_EQ(j["runs"][1]["label"], "plugin:path=librelaxation.so,iterations=8");
  EXPECT_TRUE(j["runs"][1]["counters"].contains("pushes")) << j["runs"][1]["counters"];
  EXPECT_NE(run.out.find("pushes"), std::string::npos) << run.out;  // a column of the table

  const std::string sweep_json = temp("plugin_sweep.json");
  const Result sweep = chainbench("sweep --scene stack --set n=3 --steps 30 --grid \"" +
                                  kRelaxation + ";iterations=1,4\" --json " + sweep_json);
  ASSERT_EQ(sweep.status, 0) << sweep.out;
  nlohmann::json s;
  std::ifstream(sweep_json) >> s;
  EXPECT_EQ(s["scenes"][0]["points"].size(), 2u) << s.dump().substr(0, 2000);

  const Result stress =
      chainbench("stress --quick --filter projectile --engines chain," + kRelaxation);
  EXPECT_EQ(stress.status, 0) << stress.out;
  EXPECT_NE(stress.out.find("plugin:path=librelaxation.so"), std::string::npos) << stress.out;
}

// A key the plugin does not declare, or a value out of its range, stops the command as the spec
// is read: exit 2 naming the plugin, the key and why, before any engine runs (no scene header,
// no row of the chain engine listed before it).
TEST(Cli, ABadPluginKeyIsRefusedBeforeAnyEngineRuns) {
  const std::string plugin =
      std::string("plugin:path=") + CHAINBENCH_TEST_PLUGINS + "/libtest_plugin_none.so";
  for (const auto& [keys, message] :
       {std::pair<std::string, std::string>{"bogus=1", "unknown key \"bogus\" for plugin"},
        {"gain=11", "gain: 11 is out of range [0, 10]"}}) {
    SCOPED_TRACE(keys);
    const Result r = chainbench("run --scene stack --set n=2 --engines chain," + plugin + "," +
                                keys + " --reference none");
    EXPECT_EQ(r.status, 2) << r.out;
    EXPECT_NE(r.out.find(message), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("libtest_plugin_none.so"), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("scene stack"), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("ms/step"), std::string::npos) << r.out;
  }
}

TEST(Cli, PluginFaultsExitTwoWithTheirReason) {
  const std::string dir = CHAINBENCH_TEST_PLUGINS;
  for (const auto& [fault, message] :
       {std::pair<std::string, std::string>{"missing", "no such file"},
        {"no_entry", "exports no chainbench_engine_plugin()"},
        {"abi", "built for plugin ABI 3, this chainbench loads ABI 2"},
        {"abi1", "built for plugin ABI 1, this chainbench loads ABI 2"},
        // (A fault once the plugin steps, a NaN state say, is its error row and exit status 1:
        // cli_isolated_test.cpp.)
        {"create", "this plugin builds no worlds"}}) {
    SCOPED_TRACE(fault);
    const Result r = chainbench("run --scene stack --set n=2 --engines plugin:path=" + dir +
                                "/libtest_plugin_" + fault + ".so --reference none");
    EXPECT_EQ(r.status, 2) << r.out;
    EXPECT_NE(r.out.find(message), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("internal error"), std::string::npos) << r.out;
  }
}

}  // namespace

// merge checks the form of each part's results and shard block, naming file, field and reason,
// rather than failing on a JSON type error or merging a point it cannot read.
TEST(Cli, MergeNamesAMalformedPartsFieldAndWhy) {
  const std::string part = ::testing::TempDir() + "cb_merge_part.json";
  const Result ran =
      chainbench("sweep --scene stack --grid chain:passes=1,2 --shard 1/2 --json " + part);
  ASSERT_EQ(ran.status, 0) << ran.out;
  nlohmann::ordered_json good;
  std::ifstream(part) >> good;
  auto refused = [&](nlohmann::ordered_json bad, const std::string& message) {
    const std::string path = ::testing::TempDir() + "cb_merge_bad.json";
    std::ofstream(path) << bad.dump();
    const Result r = chainbench("merge " + path);
    EXPECT_EQ(r.status, 2) << r.out;
    EXPECT_NE(r.out.find(path + ": " + message), std::string::npos) << r.out;
  };
  nlohmann::ordered_json bogus_point = good;
  bogus_point["scenes"][0]["points"][0] = {{"bogus", 1}};
  refused(bogus_point, "scenes[0].points[0].engine: missing (should be a string)");
  nlohmann::ordered_json string_shard = good;
  string_shard["shard"] = "1/2";
  refused(string_shard, "shard: should be an object, got string");
  nlohmann::ordered_json bad_index = good;
  bad_index["shard"]["index"] = "one";
  refused(bad_index, "shard.index: should be a whole number, got string");
  // Numbers that do not fit, without narrowing, and a unit listed twice.
  nlohmann::ordered_json big_count = good;
  big_count["shard"]["count"] = 4294967298u;
  refused(big_count, "shard.count: 4294967298 is outside [-2147483647, 2147483647]");
  nlohmann::ordered_json negative_units = good;
  negative_units["shard"]["units"] = -1;
  refused(negative_units, "shard.units: -1 is outside [0, 2147483647]");
  nlohmann::ordered_json twice = good;
  twice["shard"]["ran"].push_back(twice["shard"]["ran"][0]);
  refused(twice, "shard.ran: unit 0 listed twice");
  // Text no JSON library hands over as a value: refused as read, naming the file.
  auto refused_text = [&](const std::string& text, const std::string& message) {
    const std::string path = ::testing::TempDir() + "cb_merge_text.json";
    std::ofstream(path) << text;
    const Result r = chainbench("merge " + path);
    EXPECT_EQ(r.status, 2) << r.out.substr(0, 2000);
    EXPECT_NE(r.out.find(path + ": " + message), std::string::npos) << r.out.substr(0, 2000);
  };
  refused_text("{\"shard\": 1e400}", "holds a number beyond double range");
  refused_text(std::string(100000, '[') + std::string(100000, ']'), "nested deeper than 64 levels");
}

TEST(Cli, SweepVaryRunsEachSceneOncePerValueAndNamesItEverywhere) {
  const std::string json_path = temp("vary.json"), csv_path = temp("vary.csv");
  const Result r = chainbench(
      "sweep --scene stack --set n=3 --vary dt=1/30,1/120 --grid chain:passes=1,4 --json " +
      json_path + " --csv " + csv_path);
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("scene stack (dt=1/30): "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("scene stack (dt=1/120): "), std::string::npos) << r.out;
  nlohmann::json j;
  std::ifstream(json_path) >> j;
  ASSERT_EQ(j["scenes"].size(), 2u);
  // Each value keeps the default run's simulated time (600 steps at 1/60 s: 10 s).
  const int steps[] = {300, 1200};
  for (int k = 0; k < 2; ++k) {
    const auto& scene = j["scenes"][k]["scene"];
    EXPECT_EQ(scene["vary"]["key"], "dt");
    EXPECT_EQ(scene["vary"]["text"], k == 0 ? "1/30" : "1/120");
    EXPECT_EQ(scene["vary"]["value"].get<double>(), k == 0 ? 1.0 / 30 : 1.0 / 120);
    EXPECT_EQ(scene["steps"], steps[k]);
    EXPECT_EQ(j["scenes"][k]["points"].size(), 2u);
  }
  std::ifstream csv(csv_path);
  std::string header, row;
  std::getline(csv, header);
  std::getline(csv, row);
  EXPECT_EQ(header.substr(header.size() - 13), ",vary,verdict");
  EXPECT_EQ(row.substr(row.size() - 11), ",dt=1/30,ok");

  const Result bad = chainbench("sweep --scene stack --vary dt=1/30,1/30");
  EXPECT_EQ(bad.status, 2) << bad.out;
  EXPECT_NE(bad.out.find("--vary dt: value 1/30 given twice"), std::string::npos) << bad.out;
  const Result file = chainbench("sweep --scene-file " + std::string(CHAINBENCH_EXAMPLES) +
                                 "/push_two.json --vary dt=1/30");
  EXPECT_EQ(file.status, 2) << file.out;
  EXPECT_NE(file.out.find("--vary applies to built-in scenes"), std::string::npos) << file.out;
}

TEST(Cli, DefaultsInAnEngineListStandForTheDefaultEngines) {
  const std::string json_path = temp("defaults.json");
  const Result r = chainbench(
      "run --scene stack --set n=3 --set steps=10 --engines "
      "defaults,chipmunk:sleep=1,chain --json " +
      json_path);
  ASSERT_EQ(r.status, 0) << r.out;
  nlohmann::json j;
  std::ifstream(json_path) >> j;
  std::vector<std::string> labels;
  for (const auto& run : j["runs"])
    labels.push_back(run["label"]);
  // The defaults in their order, the ones named after them; chain, named again, runs once.
  std::vector<std::string> expected = {"chain:variant=seed2014", "box2d", "chipmunk"};
  if (CHAINBENCH_BOX2D3_BUILT) expected.push_back("box2d3");
  expected.insert(expected.end(), {"chipmunk:sleep=1", "chain"});
  EXPECT_EQ(labels, expected);
  for (const auto& run : j["runs"]) {
    const bool chipmunk = run["engine"].get<std::string>().rfind("chipmunk", 0) == 0;
    EXPECT_EQ(run.contains("caveat"), chipmunk) << run["label"];
  }
  EXPECT_EQ(j["scene"]["family"], "stacking");

  // A default that cannot run the scene is left out with a note, as with no list.
  const Result friction = chainbench(
      "run --scene stack --set n=3 --set steps=10 --set friction=0.5 --engines "
      "defaults,box2d:sleep=1");
  EXPECT_EQ(friction.status, 0) << friction.out;
  EXPECT_NE(friction.out.find("chain:variant=seed2014 left out"), std::string::npos)
      << friction.out;
  const Result twice = chainbench("run --scene stack --engines defaults,defaults");
  EXPECT_EQ(twice.status, 2) << twice.out;
  EXPECT_NE(twice.out.find("defaults given twice"), std::string::npos) << twice.out;
  const Result keys = chainbench("run --scene stack --engines defaults,sleep=1");
  EXPECT_EQ(keys.status, 2) << keys.out;
  EXPECT_NE(keys.out.find("follows defaults, which takes no keys"), std::string::npos) << keys.out;
}
