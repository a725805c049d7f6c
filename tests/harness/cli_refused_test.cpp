// SPDX-License-Identifier: MIT
// Calls the chainbench command refuses: each exits with status 2 and says why.
#include "cli_run.h"

#include <gtest/gtest.h>

#include <ostream>
#include <string>

namespace {

using cli::chainbench;
using cli::Result;

struct BadCall {
  const char* args;
  const char* message;  // a part of what the command must print
};
void PrintTo(const BadCall& c, std::ostream* os) {
  *os << c.args;
}

// A plain array of literals: ValuesIn() over it compiles in a fraction of the time that a
// Values() call of as many arguments takes.
constexpr BadCall kBadCalls[] = {
    {"run", "give --scene NAME or --scene-file FILE"},
    {"run --scene nope", "unknown scene \"nope\""},
    {"run --scene stack --set n=1e12", "out of range"},
    {"run --scene stack --set colour=3", "no parameter \"colour\""},
    {"run --scene stack --engines chain:speed=2", "unknown key \"speed\""},
    {"run --scene stack --engines havok", "unknown engine \"havok\""},
    {"run --scene stack --steps 0", "--steps"},
    {"run --scene stack --metrics speed", "unknown metric"},
    {"sweep --scene stack --reference none",
     "--reference none: a sweep measures each point's error"},
    {"run --scene stack --scene-file x.json", "excludes"},
    {"run --scene-file /nonexistent.json", "/nonexistent.json: no such file"},
    {"run --scene-file /tmp", "/tmp: is a directory, not a scene file"},
    {"run --scene stack --engines chain --require box2d",
     "--require box2d: not among the engines run (chain)"},
    {"run --scene stack --require chain:colour=3", "unknown key"},
    // A default the scene rules out is named with the reason it was left out.
    {"run --scene stack --set friction=0.5 --require chain:variant=seed2014",
     "--require chain:variant=seed2014: left out of the default engines, scene stack: "},
    {"run --scene stack --json /nonexistent/dir/out.json",
     "--json: cannot write /nonexistent/dir/out.json: no such directory "
     "/nonexistent/dir"},
    {"run --scene stack --csv /tmp", "--csv: cannot write /tmp: is a directory"},
    {"run --scene stack --trace /nonexistent/t.csv",
     "--trace: cannot write /nonexistent/t.csv: no such directory"},
    {"replay --scene stack --out /nonexistent/x.html", "no such directory"},
    {"run --scene stack --json -", "give a file name"},
    {"run --scene stack --set n=abc", "\"abc\" is not a number"},
    {"run --scene stack --set n=2.5", "whole number"},
    {"run --scene stack --set size=NaN", "not a finite number"},
    {"run --scene stack --set size=1e999", "not a finite number"},
    {"run --scene stack --set size=0", "out of range [0.01, 100]"},
    {"run --scene stack --set n", "expected KEY=VALUE"},
    {"run --scene stack --engines chain:passes=abc", "not a number"},
    {"run --scene stack --engines chain:passes=1e99", "out of range"},
    {"run --scene stack --engines chain:variant=1999", "modern|seed2014"},
    {"run --scene stack --engines ,", "empty entry"},
    {"stress --filter nothing-matches-this", "no case matches"},
    {"stress --timeout 0", "--timeout"},
    {"sweep --scene stack --grid foo=1", "unknown engine"},
    {"sweep --scene stack --shard 0/3", "--shard 0/3: expected K/N"},
    {"stress --quick --shard 2", "--shard 2: expected K/N"},
    {"sweep --scene stack --shard ''", "--shard is empty: give K/N"},
    {"stress --quick --shard ''", "--shard is empty: give K/N"},
    // --set numbers in the grammar of --steps.
    {"run --scene stack --set n=0x10", "\"0x10\" is not a number"},
    {"run --scene stack --set n=+2", "\"+2\" is not a number"},
    {"run --scene stack --set 'n= 2'", "\" 2\" is not a number"},
    {"run --scene stack --set 'n=2 '", "\"2 \" is not a number"},
    {"replay --scene stack", "--out is required"},
    {"replay --scene random_pile --set n=100000 --out /tmp/x.html", "more than a page holds"},
    {"merge /nonexistent/part.json", "/nonexistent/part.json: cannot read"},
    {"merge /tmp", "/tmp: is a directory"},
    {"frobnicate", "unknown command \"frobnicate\""},
    {"run --scene stack --engines ''",
     "--engines: no engine named (leave --engines out for the defaults)"},
    {"engines ''", "chainbench: spec: no engine named (leave SPEC out for every engine)"},
    {"run --scene stack --engines chain,chain", "chain given twice"},
    {"run --scene stack --set n=5 --set n=6", "--set n: given twice"},
    {"run --scene stack --set steps=5 --steps 6", "--steps sets it too"},
    {"sweep --scene stack --shard 1/2", "give --json FILE"},
    {"stress --quick --shard 1/2", "give --json FILE"},
    {"run --scene stack --steps abc", "chainbench: --steps: \"abc\" is not a whole number"},
    {"sweep --scene stack --steps 1.5", "--steps: \"1.5\" is not a whole number"},
    {"run --scene stack --steps 0", "--steps: 0 is outside [1, 10000000]"},
    {"run --scene stack --replay-mb x", "--replay-mb: \"x\" is not a number"},
    {"stress --timeout nan", "--timeout: nan is outside [0.001, 86400]"},
    {"run --scene random_pile --set seed=2147483648", "2147483648 is out of range [0, 2147483647]"},
    {"run --scene-file ''", "--scene-file: the scene file path is empty"},
    {"sweep --scene-file ''", "--scene-file: the scene file path is empty"},
    {"replay --scene-file '' --out /tmp/x.html", "--scene-file: the scene file path is empty"},
    {"--frob", "chainbench: unknown option --frob (commands: list, "},
    {"run --scene stack --scene pyramid", "--scene given 2 times; give it once"},
    {"run --scene stack --json /tmp/cb_same --csv /tmp/cb_same",
     "--json and --csv both name /tmp/cb_same: give each output its own file"},
    {"run --scene stack --trace /tmp/cb_same --replay /tmp/../tmp/cb_same",
     "--trace /tmp/cb_same and --replay /tmp/../tmp/cb_same name the same file"},
    {"sweep --scene stack --json /tmp/cb_same --csv /tmp/cb_same", "both name"},
    {"run --scene stack --json ''", "--json: the output file path is empty"},
    {"run --scene stack --replay ''", "--replay: the output file path is empty"},
    {"sweep --scene stack --csv ''", "--csv: the output file path is empty"},
    {"stress --quick --json ''", "--json: the output file path is empty"},
    {"replay --scene stack --out ''", "--out: the output file path is empty"},
    {"merge /tmp/x.json --json ''", "--json: the output file path is empty"},
    {"run --scene stack --replay-mb 5", "--replay-mb requires --replay"},
    {"sweep --scene stack --grid chain:passes=1,1", "--grid: point "},
    {"sweep --scene stack --grid chain:passes=1 --grid chain:passes=1", "given twice"},
    {"run --scene stack --steps 1e3 --set steps=5", "--steps sets it too"},
    {"run --scene stack --steps 1e8", "--steps: 1e8 is outside [1, 10000000]"},
    {"run --scene stack --steps nan", "--steps: \"nan\" is not a whole number"},
    {"run --scene stack --steps ''", "--steps"},
    {"run --scene stack --bogus", "chainbench: The following argument was not expected"}};

class RefusedCall : public ::testing::TestWithParam<BadCall> {};

INSTANTIATE_TEST_SUITE_P(Cli, RefusedCall, ::testing::ValuesIn(kBadCalls),
                         [](const auto& info) { return "Case" + std::to_string(info.index); });

TEST_P(RefusedCall, ExitsWithStatusTwoAndSaysWhy) {
  const Result r = chainbench(GetParam().args);
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_NE(r.out.find(GetParam().message), std::string::npos) << r.out;
}

}  // namespace
