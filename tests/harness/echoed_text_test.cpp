// SPDX-License-Identifier: MIT
// What a message echoes of an input: cut to a readable length, control characters and bytes
// that are not UTF-8 shown as \xNN, so that no input can drive the terminal or make an output
// that is not UTF-8; and engine specs, which reach plugins and JSON, refused unless UTF-8 text.
#include "engines/engine_spec.h"
#include "support/input_error.h"

#include <gtest/gtest.h>

#include <string>

namespace chainbench {
namespace {

std::string refusal(const std::string& spec) {
  try {
    parse_engine_spec(spec);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(EchoedText, ControlCharactersAndBadBytesAreShownAsHex) {
  EXPECT_EQ(cut_for_message("ab\033[2Jc"), "ab\\x1b[2Jc");
  EXPECT_EQ(cut_for_message("a\nb\x7f"), "a\\x0ab\\x7f");
  EXPECT_EQ(cut_for_message("\xff\xc3"), "\\xff\\xc3");      // not UTF-8; a lead byte alone
  EXPECT_EQ(cut_for_message("\xc0\xaf"), "\\xc0\\xaf");      // an overlong '/'
  EXPECT_EQ(cut_for_message("caf\xc3\xa9"), "caf\xc3\xa9");  // UTF-8 stays as it is
  EXPECT_EQ(cut_for_message("\xf0\x9f\x99\x82"), "\xf0\x9f\x99\x82");
}

TEST(EchoedText, LongTextIsCutAtAWholeCharacter) {
  const std::string shown = cut_for_message(std::string(79, 'a') + "\xc3\xa9" + "zzz");
  EXPECT_EQ(shown, std::string(79, 'a') + "\xc3\xa9" + "\u2026(84 bytes)");
  EXPECT_EQ(cut_for_message(std::string(80, 'k')), std::string(80, 'k'));
  EXPECT_LT(cut_for_message(std::string(100000, '\033')).size(), 400u);
}

TEST(EchoedText, TextProblemNamesTheFirstBadByte) {
  EXPECT_EQ(text_problem("plain, caf\xc3\xa9"), "");
  EXPECT_NE(text_problem("ab\xff").find("0xff at offset 2"), std::string::npos);
  EXPECT_NE(text_problem("\t").find("0x09 at offset 0"), std::string::npos);
}

TEST(EchoedText, EngineSpecsMustBeUtf8TextAndEchoTheirPartsCut) {
  EXPECT_NE(refusal("chain:variant=\xff").find("0xff at offset 14"), std::string::npos);
  EXPECT_NE(refusal("chain:variant=a\033[2J").find("0x1b"), std::string::npos);
  const std::string k(100000, 'k');
  for (const std::string& spec : {k, "chain:" + k + "=1", "chain:variant=" + k, "chain:" + k,
                                  "plugin:path=" + k, "chain:" + k + "=1," + k + "=2"}) {
    const std::string message = refusal(spec);
    EXPECT_FALSE(message.empty()) << spec.substr(0, 30);
    EXPECT_LT(message.size(), 1000u) << message.substr(0, 200);
  }
}

// Characters that show nothing or turn the text around them are shown as bytes and refused, as
// control characters are: a name holding U+202E would print its tail reversed.
TEST(EchoedText, InvisibleAndReorderingCharactersAreShownAsHexAndRefused) {
  for (const std::string c :
       {"\u200b", "\u200f", "\u2028", "\u2029", "\u202e", "\u2066", "\ufeff", "\ufff9", "\uffff"}) {
    SCOPED_TRACE(cut_for_message(c));
    const std::string text = "ok" + c + "x";
    EXPECT_EQ(cut_for_message(text).find(c), std::string::npos) << cut_for_message(text);
    EXPECT_EQ(cut_for_message(text).rfind("ok\\x", 0), 0u) << cut_for_message(text);
    EXPECT_NE(text_problem(text).find("at offset 2"), std::string::npos) << text_problem(text);
  }
  // Visible neighbours stay text: a non-breaking space, an em dash, U+2030, U+FFFD.
  for (const std::string c : {"\u00a0", "\u2014", "\u2030", "\ufffd", "\u2027"})
    EXPECT_EQ(text_problem("ok" + c), "") << cut_for_message(c);
  // Surrogates and code points above U+10FFFF are not UTF-8.
  EXPECT_NE(text_problem("\xed\xa0\x80").find("0xed at offset 0"), std::string::npos);
  EXPECT_NE(text_problem("\xf4\x90\x80\x80").find("0xf4 at offset 0"), std::string::npos);
  EXPECT_EQ(text_problem("\xf4\x8f\xbf\xbd"), "");  // U+10FFFD
}

}  // namespace
}  // namespace chainbench
