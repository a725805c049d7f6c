// SPDX-License-Identifier: MIT
// A scene file's text (scene_text.h): every string field refused, naming file, field and reason,
// when it holds control characters or bytes that are not UTF-8 or is longer than a name may be;
// a NUL byte or a UTF-16 byte order mark refused; a UTF-8 byte order mark skipped; and no message
// ever echoes what it refuses raw.
#include "scenes/scene_text.h"
#include "scenes/scene_file.h"
#include "support/input_error.h"

#include <gtest/gtest.h>

#include <string>

namespace chainbench {
namespace {

// A scene of one dynamic box, with `name` as the scene's name and `body` as the box's (both
// written into the JSON as they are: pass them escaped where JSON needs it).
std::string scene_json(const std::string& name, const std::string& body) {
  return R"({"schema":1,"name":")" + name + R"(","steps":2,"bodies":[{"name":")" + body +
         R"(","type":"dynamic","center":[0,0],"half_extents":[0.5,0.5],"mass":1}],"expect":[{"body":")" +
         body + R"(","center":[0,0],"tolerance":1}]})";
}

std::string refusal(const std::string& text) {
  try {
    parse_scene(text, "s.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// What a message may hold: UTF-8 text, lines apart, with no control character but the newline.
void expect_shown(const std::string& message) {
  std::string flat = message;
  for (char& c : flat) {
    if (c == '\n') c = ' ';
  }
  EXPECT_EQ(text_problem(flat), "") << cut_for_message(message, 1000);
}

TEST(SceneText, ControlCharactersInANameAreRefusedByField) {
  const std::string esc = refusal(scene_json("a\\u001b[2Jb", "box"));
  EXPECT_NE(esc.find("s.json: name: holds the byte 0x1b at offset 1"), std::string::npos) << esc;
  const std::string newline = refusal(scene_json("ok", "two\\nlines"));
  EXPECT_NE(newline.find("s.json: bodies[0].name: holds the byte 0x0a at offset 3"),
            std::string::npos)
      << newline;
  const std::string nul = refusal(scene_json("ok", "a\\u0000b"));
  EXPECT_NE(nul.find("bodies[0].name: holds the byte 0x00"), std::string::npos) << nul;
  const std::string c1 = refusal(scene_json("csi\\u009b", "box"));
  EXPECT_NE(c1.find("s.json: name: holds the byte 0xc2 at offset 3"), std::string::npos) << c1;
  for (const std::string& m : {esc, newline, nul, c1})
    expect_shown(m);
  // Text that is UTF-8 without control characters stays a name.
  EXPECT_EQ(parse_scene(scene_json("caf\xc3\xa9 \xf0\x9f\x99\x82", "box"), "s.json").name,
            "caf\xc3\xa9 \xf0\x9f\x99\x82");
}

TEST(SceneText, ALongNameIsRefusedWithAShortMessage) {
  const std::string huge(5'000'000, 'n');
  const std::string m = refusal(scene_json(huge, "box"));
  EXPECT_NE(m.find("s.json: name: is 5000000 bytes, more than the 256 a name may hold"),
            std::string::npos)
      << cut_for_message(m);
  EXPECT_LT(m.size(), 200u);
  const std::string body = refusal(scene_json("ok", std::string(257, 'b')));
  EXPECT_NE(body.find("bodies[0].name: is 257 bytes"), std::string::npos) << body;
  EXPECT_LT(body.size(), 400u);
  EXPECT_EQ(refusal(scene_json("ok", std::string(256, 'b'))), "");
}

TEST(SceneText, BadUtf8IsShownEscapedNeverRaw) {
  // Raw bytes that are not UTF-8: the JSON reader refuses them, and the message shows them as
  // \xNN (its own text quotes what it read last).
  const std::string m = refusal(scene_json("bad\xff\xfe", "box"));
  ASSERT_NE(m, "");
  EXPECT_EQ(m.find('\xff'), std::string::npos);
  EXPECT_NE(m.find("\\xff"), std::string::npos) << m;
  expect_shown(m);
  const std::string cut = refusal(scene_json(std::string(100000, 'x') + "\xc3", "box"));
  EXPECT_LT(cut.size(), 700u);
  expect_shown(cut);
}

TEST(SceneText, ANulByteOrAUtf16MarkIsRefusedAndAUtf8MarkSkipped) {
  const std::string good = scene_json("ok", "box");
  const std::string nul = refusal(good + std::string(1, '\0'));
  EXPECT_EQ(nul, "s.json: holds a NUL byte at offset " + std::to_string(good.size()) +
                     " (a scene file is JSON text, which has none; a file cut or padded by a "
                     "tool?)");
  // Whatever follows a NUL is not ignored either.
  EXPECT_NE(refusal(good + std::string(1, '\0') + "garbage"), "");
  EXPECT_NE(refusal("\xff\xfe" + good).find("UTF-16 or UTF-32 byte order mark"), std::string::npos);
  const Scene marked = parse_scene("\xef\xbb\xbf" + good, "s.json");
  EXPECT_EQ(marked.name, "ok");
  EXPECT_EQ(marked.bodies.at(0).name, "box");
}

}  // namespace
}  // namespace chainbench
