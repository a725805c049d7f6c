// SPDX-License-Identifier: MIT
// The default suite is named once, in the scene library; `chainbench list --suite default` is how
// the scripts read it.
#include "cli_run.h"
#include "scenes/scene_library.h"

#include <gtest/gtest.h>

#include <string>

namespace {

TEST(CliSuite, ListSuitePrintsTheDefaultSuiteOneNameALine) {
  const cli::Result r = cli::chainbench("list --suite default");
  ASSERT_EQ(r.status, 0) << r.out;
  std::string expected;
  for (const std::string& name : chainbench::default_suite())
    expected += name + "\n";
  EXPECT_EQ(r.out, expected);
  const cli::Result bad = cli::chainbench("list --suite everything");
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.out.find("--suite"), std::string::npos) << bad.out;
}

}  // namespace

namespace {

// `list --metrics` prints the metric table the docs hold (docs/output-formats.md §2.5).
TEST(CliSuite, ListMetricsPrintsTheMetricTable) {
  const cli::Result r = cli::chainbench("list --metrics");
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_EQ(r.out.rfind("| key | run CSV | group | unit |", 0), 0u) << r.out;
  for (const char* key : {"`max_penetration`", "`energy_free_displacement.per_body_step`",
                          "`tunnelling`", "`escaped`"}) {
    EXPECT_NE(r.out.find(key), std::string::npos) << key;
  }
  EXPECT_EQ(cli::chainbench("list --metrics --suite default").status, 2);
}

}  // namespace
