// SPDX-License-Identifier: MIT
// TextTable: tables of numbers right-aligned; tables of text (wrap_text) left-aligned with the last
// column wrapped within the width, none of its words lost.
#include "support/text_table.h"

#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

namespace {

using chainbench::TextTable;

std::vector<std::string> lines_of(const TextTable& t) {
  std::ostringstream out;
  t.print(out);
  std::istringstream in(out.str());
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);)
    lines.push_back(line);
  return lines;
}

TEST(TextTable, NumbersAreRightAligned) {
  TextTable t({"engine", "ms"});
  t.add({"chain", "0.5"});
  t.add({"box2d", "12.25"});
  const std::vector<std::string> lines = lines_of(t);
  ASSERT_EQ(lines.size(), 4u);
  EXPECT_EQ(lines[0], "engine     ms");
  EXPECT_EQ(lines[2], "chain     0.5");
  EXPECT_EQ(lines[3], "box2d   12.25");
}

TEST(TextTable, TextIsLeftAlignedAndItsLastColumnWrapsWithinTheWidth) {
  const std::string help =
      "continuous collision: 0 off, 1 against static bodies, 2 every dynamic body a bullet";
  TextTable t({"  key", "default", "meaning"});
  t.add({"  ccd", "1", help});
  t.add({"  warm", "0", "warm starting"});
  t.wrap_text(45);
  const std::vector<std::string> lines = lines_of(t);
  // The key and default columns and their gaps take 17 columns: the help has the 28 left.
  const std::size_t start = 17;
  ASSERT_EQ(lines.size(), 6u);  // the help in 3 lines
  EXPECT_EQ(lines[0], "  key   default  meaning");
  EXPECT_EQ(lines[1], std::string(45, '-'));
  EXPECT_EQ(lines[2], "  ccd   1        continuous collision: 0 off,");
  EXPECT_EQ(lines.back(), "  warm  0        warm starting");
  std::string joined;
  for (std::size_t i = 2; i + 1 < lines.size(); ++i) {
    EXPECT_LE(lines[i].size(), 45u) << lines[i];
    if (i > 2) {
      EXPECT_EQ(lines[i].substr(0, start), std::string(start, ' ')) << lines[i];
    }
    joined += (joined.empty() ? "" : " ") + lines[i].substr(start);
  }
  EXPECT_EQ(joined, help);  // every word, in order, none cut: each fits the room
}

// Where the help alone cannot make room, the widest of the others gives the rest: the default here
// wraps too, never below its longest word ("variant=seed2014"), the values column not at all.
TEST(TextTable, TheWidestColumnsNarrowInTurnUntilTheTableFits) {
  TextTable t({"  key", "values", "default", "meaning"});
  t.add({"  velocity", "zero|inelastic", "inelastic, zero if variant=seed2014",
         "velocity after a push: momentum shared"});
  t.wrap_text(76);
  // 103 columns unwrapped: the help gives 14, down to 24; the default, the widest left, the other
  // 13, to 22.
  const std::vector<std::string> lines = lines_of(t);
  ASSERT_EQ(lines.size(), 4u);
  EXPECT_EQ(lines[0], "  key       values          default                 meaning");
  EXPECT_EQ(lines[1], std::string(76, '-'));
  EXPECT_EQ(lines[2], "  velocity  zero|inelastic  inelastic, zero if      velocity after a push:");
  EXPECT_EQ(lines[3], std::string(28, ' ') + "variant=seed2014        momentum shared");
}

TEST(TextTable, AWordLongerThanTheRoomIsCutAcrossLines) {
  const std::string word(60, 'x');
  TextTable t({"k", "meaning"});
  t.add({"a", "see " + word + " there"});
  t.wrap_text(30);  // room: 30 - 3 = 27 columns
  const std::vector<std::string> lines = lines_of(t);
  ASSERT_EQ(lines.size(), 6u);
  EXPECT_EQ(lines[2], "a  see");
  EXPECT_EQ(lines[1], std::string(30, '-'));
  EXPECT_EQ(lines[3], "   " + std::string(27, 'x'));
  EXPECT_EQ(lines[4], "   " + std::string(27, 'x'));
  EXPECT_EQ(lines[5], "   xxxxxx there");
}

}  // namespace
