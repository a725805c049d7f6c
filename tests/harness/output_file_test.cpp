// SPDX-License-Identifier: MIT
// Output files, whole or not at all: the target changes only when an output is committed, keeps
// its mode and its symbolic link, and no temporary outlives its output.
#include "support/output_file.h"
#include "support/input_error.h"
#include "test_files.h"

#include <gtest/gtest.h>

#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace chainbench {
namespace {

namespace fs = std::filesystem;

// A folder of this test's own, emptied.
std::string folder(const std::string& name) {
  return test::fresh_folder("chainbench_output_" + name);
}

std::size_t files_in(const std::string& dir) {
  return static_cast<std::size_t>(
      std::distance(fs::directory_iterator(dir), fs::directory_iterator()));
}

TEST(OutputFile, AnOutputNotCommittedLeavesThePreviousFileAndNoTemporary) {
  const std::string dir = folder("uncommitted");
  std::ofstream(dir + "out.json") << "previous";
  {
    const auto out = open_output(dir + "out.json", "--json");
    out->stream() << "half of a new fi";
    EXPECT_EQ(files_in(dir), 2u);  // the target and its temporary
    EXPECT_EQ(test::read_file(dir + "out.json"), "previous");
  }  // an error unwinds past it
  EXPECT_EQ(test::read_file(dir + "out.json"), "previous");
  EXPECT_EQ(files_in(dir), 1u);
}

TEST(OutputFile, ACommittedOutputReplacesItsTargetKeepingModeAndLink) {
  const std::string dir = folder("committed");
  std::ofstream(dir + "real.csv") << "previous";
  fs::permissions(dir + "real.csv", fs::perms(0640));
  fs::create_symlink(dir + "real.csv", dir + "link.csv");
  const auto out = open_output(dir + "link.csv", "--csv");
  const auto fresh = open_output(dir + "new.csv", "--json");
  out->stream() << "new";
  fresh->stream() << "fresh";
  commit_outputs({out.get(), fresh.get()});
  EXPECT_TRUE(fs::is_symlink(dir + "link.csv"));
  EXPECT_EQ(test::read_file(dir + "real.csv"), "new");
  EXPECT_EQ(test::read_file(dir + "new.csv"), "fresh");
  EXPECT_EQ(fs::status(dir + "real.csv").permissions() & fs::perms::all, fs::perms(0640));
  EXPECT_EQ(files_in(dir), 3u);
}

// A link to a file not there yet stays a link: the file it names is made, link by link, and a
// link into a folder that does not exist is refused naming that folder. A link to a descriptor
// that is not open (/dev/stdout while standard output is closed) is never replaced by a file.
TEST(OutputFile, ALinkToNothingIsFollowedNeverReplaced) {
  const std::string dir = folder("dangling");
  fs::create_directory(dir + "there");
  fs::create_symlink(dir + "there/made.csv", dir + "second");
  fs::create_symlink("second", dir + "first");  // relative, two hops
  const auto out = open_output(dir + "first", "--csv");
  out->stream() << "made";
  commit_outputs({out.get()});
  EXPECT_TRUE(fs::is_symlink(dir + "first"));
  EXPECT_TRUE(fs::is_symlink(dir + "second"));
  EXPECT_EQ(test::read_file(dir + "there/made.csv"), "made");
  fs::create_symlink(dir + "nowhere/x.csv", dir + "lost");
  try {
    open_output(dir + "lost", "--csv");
    ADD_FAILURE() << "a link into a missing folder was taken";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no such directory " + dir + "nowhere"), std::string::npos)
        << e.what();
  }
  EXPECT_TRUE(fs::is_symlink(dir + "lost"));
  // A descriptor no process has open: its name leads nowhere, and nothing is made there.
  fs::create_symlink("/proc/self/fd/987654", dir + "closed");
  try {
    open_output(dir + "closed", "--trace");
    ADD_FAILURE() << "a link to a closed descriptor was taken";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("names no open device or descriptor"), std::string::npos)
        << e.what();
  }
  EXPECT_TRUE(fs::is_symlink(dir + "closed"));
}

// What a command takes back (a trace's rows of an engine that did not finish) is gone from the
// file, and what it writes next follows what it kept, however large the part dropped.
TEST(OutputFile, CutBackDropsWhatWasWrittenAfterAMark) {
  const std::string dir = folder("cut_back");
  const auto out = open_output(dir + "t.csv", "--trace");
  out->stream() << "header\nfinished,1\n";
  const long long kept = out->written();
  EXPECT_EQ(kept, 18);
  out->stream() << std::string(1 << 20, 'u');  // more than a stream buffer: some reached the disk
  ASSERT_TRUE(out->cut_back(kept));
  EXPECT_EQ(out->written(), kept);
  out->stream() << "# end\n";
  commit_outputs({out.get()});
  EXPECT_EQ(test::read_file(dir + "t.csv"), "header\nfinished,1\n# end\n");
  // Written directly, nothing can be taken back: the caller is told.
  const auto device = open_output("/dev/null", "--trace");
  EXPECT_EQ(device->written(), -1);
  EXPECT_FALSE(device->cut_back(0));
}

TEST(OutputFile, ADeviceIsWrittenDirectly) {
  const auto out = open_output("/dev/null", "--json");
  out->stream() << "nothing";
  commit_outputs({out.get()});
  EXPECT_TRUE(fs::is_character_file("/dev/null"));
}

TEST(OutputFile, AFullDeviceIsAnOutputError) {
  const auto out = open_output("/dev/full", "--json");
  out->stream() << std::string(1 << 16, 'x');
  EXPECT_THROW(commit_outputs({out.get()}), OutputError);
}

TEST(OutputFile, AnOutputThatNamesAnInputOrAnotherOutputIsRefused) {
  const std::string dir = folder("clash");
  std::ofstream(dir + "s.json") << "{}";
  fs::create_hard_link(dir + "s.json", dir + "hard.json");
  const std::string scene = dir + "s.json", dotted = dir + "./s.json", hard = dir + "hard.json";
  const std::string other = dir + "other.json",
                    again = dir + "../chainbench_output_clash/other.json";
  EXPECT_THROW(refuse_clashing_files({{"--json", &dotted}}, {{"--scene-file", &scene}}),
               InputError);
  EXPECT_THROW(refuse_clashing_files({{"--json", &hard}}, {{"--scene-file", &scene}}), InputError);
  EXPECT_THROW(refuse_clashing_files({{"--json", &other}, {"--csv", &again}}), InputError);
  EXPECT_NO_THROW(refuse_clashing_files({{"--json", &other}}, {{"--scene-file", &scene}}));
}

}  // namespace
}  // namespace chainbench
