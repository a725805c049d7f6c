// SPDX-License-Identifier: MIT
// The one exact number text (support/number_text.h): it reads back to the same bits, it has no
// digit more than that needs, whole numbers are written in full, and a message refusing a value
// just past its bound shows the value as given, not the bound.
#include "support/number_text.h"
#include "scenes/scene_file.h"
#include "scenes/scene_library.h"
#include "support/input_error.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <random>
#include <string>

namespace chainbench {
namespace {

double read_back(const std::string& text) {
  return std::strtod(text.c_str(), nullptr);
}

// Significant digits of a plain or scientific decimal text.
int significant_digits(const std::string& text) {
  const std::size_t e = text.find_first_of("eE");
  std::string mantissa = text.substr(0, e);
  std::string digits;
  for (char c : mantissa)
    if (c >= '0' && c <= '9') digits += c;
  const std::size_t first = digits.find_first_not_of('0');
  if (first == std::string::npos) return 1;
  digits = digits.substr(first);
  // Trailing zeros of a whole number's plain form count (they are its digits); of a fraction's
  // mantissa they would not be written.
  return static_cast<int>(digits.size());
}

TEST(NumberText, ReadsBackToTheSameBitsWithNoDigitTooMany) {
  std::mt19937_64 random(20261203);
  std::uniform_int_distribution<std::uint64_t> any_bits;
  for (int k = 0; k < 20000; ++k) {
    const double v = std::bit_cast<double>(any_bits(random));
    if (!std::isfinite(v)) continue;
    const std::string text = exact_number(v);
    ASSERT_EQ(std::bit_cast<std::uint64_t>(read_back(text)), std::bit_cast<std::uint64_t>(v))
        << text;
    // Whole numbers are written in full below 1e15 (tested below), and up to about 1e21 the plain
    // form is still the fewer characters: to_chars writes them plain, every digit.
    if (v == std::floor(v) && text.find('e') == std::string::npos) continue;
    // No shorter precision reads back: the text's digits are all needed.
    const int digits = significant_digits(text);
    if (digits > 1) {
      char shorter[40];
      std::snprintf(shorter, sizeof shorter, "%.*e", digits - 2, v);
      EXPECT_NE(read_back(shorter), v) << text << " could be " << shorter;
    }
  }
}

TEST(NumberText, WholeNumbersAreWrittenInFull) {
  EXPECT_EQ(exact_number(0.0), "0");
  EXPECT_EQ(exact_number(1000000.0), "1000000");
  EXPECT_EQ(exact_number(2147483648.0), "2147483648");
  EXPECT_EQ(exact_number(-100000.0), "-100000");
  EXPECT_EQ(exact_number(999999999999999.0), "999999999999999");
  EXPECT_EQ(exact_number(1e15), "1e+15");  // beyond, the shortest text
  EXPECT_EQ(exact_number(1e300), "1e+300");
}

TEST(NumberText, FractionsKeepEveryDigitTheyNeed) {
  EXPECT_EQ(exact_number(0.1), "0.1");
  EXPECT_EQ(exact_number(1.0000001), "1.0000001");
  EXPECT_EQ(exact_number(1000000.5), "1000000.5");
  EXPECT_EQ(exact_number(1.0 / 60.0), "0.016666666666666666");
  EXPECT_EQ(exact_number(1e-6), "1e-06");
  EXPECT_EQ(exact_number(5e-324), "5e-324");
}

TEST(NumberText, NonFiniteValuesAreSpelled) {
  EXPECT_EQ(exact_number(std::numeric_limits<double>::quiet_NaN()), "nan");
  EXPECT_EQ(exact_number(HUGE_VAL), "inf");
  EXPECT_EQ(exact_number(-HUGE_VAL), "-inf");
}

TEST(NumberText, AppendingWritesTheSameText) {
  std::string line = "x=";
  append_exact_number(line, 1.0000001);
  line += ',';
  append_exact_number(line, 1e6);
  EXPECT_EQ(line, "x=1.0000001,1000000");
}

std::string refusal(const std::string& scene) {
  try {
    parse_scene(scene, "f.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// A value just past its bound is shown as given: "got 1" for dt 1.0000001 would read as if the
// bound itself were refused.
TEST(NumberText, AValueJustPastItsBoundIsShownAsGiven) {
  const std::string head = R"({"schema": 1, "name": "n", "steps": 10, )";
  const std::string box =
      R"("type": "dynamic", "center": [0, 0], "half_extents": [0.5, 0.5], "mass": 1)";
  const std::string dt =
      refusal(head + R"("dt": 1.0000001, "bodies": [{"name": "a", )" + box + "}]}");
  EXPECT_NE(dt.find("f.json: dt: must be in [1e-06, 1] s, got 1.0000001"), std::string::npos) << dt;
  const std::string speed =
      refusal(head + R"("bodies": [{"name": "a", )" + box + R"(, "velocity": [100000.5, 0]}]})");
  EXPECT_NE(speed.find("bodies[0].velocity[0]: must be within +-1e5 m/s, got 100000.5"),
            std::string::npos)
      << speed;
  try {
    make_scene("pyramid", {"dt=1.0000001"});
    ADD_FAILURE() << "dt=1.0000001 was taken";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("1.0000001 is out of range"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace chainbench
