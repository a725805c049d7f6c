// SPDX-License-Identifier: MIT
// `chainbench engines [SPEC]`: what each engine takes, can do and counts, in tables that fit a
// terminal 100 columns wide.
#include "cli_run.h"

#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

namespace {

using cli::chainbench;
using cli::Result;

// The lines of a listing longer than 100 columns, other than those that are not tables: an
// engine's description, caveat, canonical spec and what it can do, each a line of its own.
std::string overlong_table_lines(const std::string& out) {
  std::istringstream lines(out);
  std::string line, overlong;
  bool first = true;
  while (std::getline(lines, line)) {
    const std::size_t text = line.find_first_not_of(' ');
    const bool not_table =
        first || line.find(" can do: ") != std::string::npos ||
        (text != std::string::npos &&
         (line.compare(text, 8, "caveat: ") == 0 || line.compare(text, 10, "canonical:") == 0 ||
          line.compare(text, 18, "canonical default:") == 0 ||
          line.compare(text, 7, "can do:") == 0));
    first = false;
    if (!not_table && line.size() > 100) overlong += line + "\n";
  }
  return overlong;
}

// `chainbench engines SPEC` lists one engine: each key with its type, range, default and help,
// what it can do and what it counts (a plugin's as its library declares them, under its own name).
TEST(Cli, EnginesSpecListsOneEnginesKeysCapabilitiesAndCounters) {
  const std::string dir = CHAINBENCH_TEST_PLUGINS;
  const Result plugin = chainbench("engines plugin:path=" + dir + "/libtest_plugin_none.so");
  ASSERT_EQ(plugin.status, 0) << plugin.out;
  // Text columns left-aligned; what the spec sets where it is not the default, a file by its name
  // (the canonical line has its path).
  for (const char* line :
       {"name: ballistic (as its library declares it)\n",
        "  key       type     values        default     given                   meaning\n",
        "  path      file     a file        (required)  libtest_plugin_none.so  the plugin's",
        "  gain      number   [0, 10]       1                                   a gain, from 0 to "
        "10\n",
        "  substeps  integer  [1, 8] whole  1                                   sub-steps per "
        "step\n",
        "  label     text     text          none                                echo: refuse",
        "can do: kinematic bodies, per-axis drives", "  steps_sum     sum over the run",
        "  steps_last    last step            steps taken, last"})
    EXPECT_NE(plugin.out.find(line), std::string::npos) << line << "\n" << plugin.out;
  // The spec's own values are shown beside the defaults.
  const Result given = chainbench("engines plugin:path=" + dir + "/libtest_plugin_none.so,gain=3");
  EXPECT_NE(given.out.find("  gain      number   [0, 10]       1           3                       "
                           "a gain"),
            std::string::npos)
      << given.out;
  EXPECT_NE(given.out.find("canonical: plugin:path=" + dir +
                           "/libtest_plugin_none.so,gain=3,"
                           "substeps=1,label=none"),
            std::string::npos)
      << given.out;
  const Result box2d = chainbench("engines box2d");
  EXPECT_EQ(box2d.status, 0) << box2d.out;
  EXPECT_NE(box2d.out.find("  vel_iters  integer  [1, 1000] whole  8                  velocity"),
            std::string::npos)
      << box2d.out;
  EXPECT_NE(box2d.out.find("  contacts  mean per step  touching contacts"), std::string::npos)
      << box2d.out;
  EXPECT_EQ(box2d.out.find("name: "), std::string::npos) << box2d.out;  // its name is its own
  // A plugin whose table is bad, or an engine that does not exist, is refused as in a run.
  const Result bad = chainbench("engines plugin:path=" + dir + "/libtest_plugin_key_type.so");
  EXPECT_EQ(bad.status, 2) << bad.out;
  EXPECT_NE(bad.out.find("key substeps: its type is 7"), std::string::npos) << bad.out;
  EXPECT_EQ(chainbench("engines nosuch").status, 2);
}

// Help wraps in its own column: box2d's key table and the whole listing's tables (whose longest
// help runs past 100 columns unwrapped) keep within 100, with every word of the help kept.
TEST(Cli, EnginesTablesFitAHundredColumns) {
  const std::string dir = CHAINBENCH_TEST_PLUGINS;
  for (const std::string& args :
       std::vector<std::string>{"engines", "engines chain", "engines box2d", "engines chipmunk",
                                "engines plugin:path=" + dir + "/libtest_plugin_none.so"}) {
    const Result r = chainbench(args);
    ASSERT_EQ(r.status, 0) << args << "\n" << r.out;
    EXPECT_EQ(overlong_table_lines(r.out), "") << args;
  }
  // chain's threads key: its help, 78 characters, on three lines of 31 columns at most.
  const Result chain = chainbench("engines");
  EXPECT_NE(chain.out.find("threads a step runs on, the\n"), std::string::npos) << chain.out;
  EXPECT_NE(chain.out.find(std::string(69, ' ') + "caller's included (same bits\n"),
            std::string::npos)
      << chain.out;
}

// A declared default outside its key's range names the plugin, its library, the key and the field
// once each, and why.
TEST(Cli, EnginesSpecNamesABadDefaultsKeyOnce) {
  const std::string dir = CHAINBENCH_TEST_PLUGINS;
  const Result r = chainbench("engines plugin:path=" + dir + "/libtest_plugin_key_default.so");
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_NE(r.out.find("chainbench: plugin ballistic (" + dir +
                       "/libtest_plugin_key_default.so): key gain: its default: 20 is out of "
                       "range [0, 10]\n"),
            std::string::npos)
      << r.out;
  EXPECT_EQ(r.out.find("gain"), r.out.rfind("gain")) << r.out;
}

}  // namespace
