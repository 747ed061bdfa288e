// Echoed user text: one line, readable, bounded (docs/robustness.md, "One line, exit 2").
#include "errors.h"

#include <gtest/gtest.h>

#include <string>

namespace omnicam {
namespace {

TEST(Quote, PlainTextIsOnlyQuoted) {
  EXPECT_EQ(quote("grey"), "\"grey\"");
  EXPECT_EQ(quote(""), "\"\"");
}

TEST(Quote, EscapesBackslashQuoteAndControlCharacters) {
  EXPECT_EQ(quote("a\\b\"c"), R"("a\\b\"c")");
  EXPECT_EQ(quote("l1\nl2\tx\ry"), R"("l1\nl2\tx\ry")");
  EXPECT_EQ(quote(std::string("a\x01" "b\x1f" "c\x7f", 6)), R"("a\x01b\x1Fc\x7F")");
  EXPECT_EQ(quote(std::string("nul\0!", 5)), R"("nul\x00!")");
}

TEST(Quote, KeepsValidUtf8AndEscapesTheRest) {
  EXPECT_EQ(quote("Kühlschrank 北 🤖"), "\"Kühlschrank 北 🤖\"");
  EXPECT_EQ(quote("a\xff" "b"), R"("a\xFFb")");              // never a UTF-8 byte
  EXPECT_EQ(quote("\xc3"), R"("\xC3")");                     // a sequence cut short
  EXPECT_EQ(quote("\xc3(x"), R"("\xC3(x")");                 // a lead without continuation
  EXPECT_EQ(quote("\xc0\xaf"), R"("\xC0\xAF")");             // overlong '/'
  EXPECT_EQ(quote("\xed\xa0\x80"), R"("\xED\xA0\x80")");     // a UTF-16 surrogate
  EXPECT_EQ(quote("\xf4\x90\x80\x80"), R"("\xF4\x90\x80\x80")");  // past U+10FFFF
  EXPECT_EQ(quote("\xc2\x9b" "2J"), R"("\xC2\x9B2J")");      // C1 control (CSI) escaped too
}

// What JSON can hold, judged as Python's strict UTF-8 decoder judges it.
TEST(IsValidUtf8, AcceptsUtf8AndNothingElse) {
  for (const char* valid : {"", "plain/path.json", "Kühlschrank 北 🤖", "\xf4\x8f\xbf\xbf", "\xc2\x9b"})
    EXPECT_TRUE(isValidUtf8(valid)) << quote(valid);
  for (const char* invalid : {"a\xff" "b", "\xc3", "\xc3(x", "\xc0\xaf", "\xed\xa0\x80", "\xf4\x90\x80\x80", "\xe2\x82"})
    EXPECT_FALSE(isValidUtf8(invalid)) << quote(invalid);
}

TEST(Quote, ShortensLongTextAtACharacterBoundaryAndSaysHowLong) {
  const std::string long300(300, 'x');
  EXPECT_EQ(quote(long300), "\"" + std::string(60, 'x') + "…\" (300 bytes)");
  EXPECT_EQ(quote(std::string(60, 'x')), "\"" + std::string(60, 'x') + "\"");
  // An escape is never cut: "ab\n" takes 4 columns, so with 3 only "ab" fits.
  EXPECT_EQ(quote("ab\ncd", 3), "\"ab…\" (5 bytes)");
  // Nor is a UTF-8 character: each "é" is one column, two bytes.
  EXPECT_EQ(quote("éééé", 2), "\"éé…\" (8 bytes)");
  EXPECT_EQ(quote("a\x01" "bc", 4), "\"a…\" (4 bytes)");
}

TEST(ShowPath, CleanPathsAreShownAsTheyAre) {
  EXPECT_EQ(showPath("/data/scenes/hall.json"), "/data/scenes/hall.json");
  EXPECT_EQ(showPath("my \"odd\" dir\\x.png"), "my \"odd\" dir\\x.png");  // nothing to escape
  EXPECT_EQ(showPath("Räume/北.png"), "Räume/北.png");
}

TEST(ShowPath, PathsThatNeedEscapingOrAreLongAreQuoted) {
  EXPECT_EQ(showPath("out/a\nb.png"), R"("out/a\nb.png")");
  EXPECT_EQ(showPath("out/\"a\"\tb"), R"("out/\"a\"\tb")");
  const std::string deep = "/" + std::string(250, 'd');
  EXPECT_EQ(showPath(deep), "\"/" + std::string(199, 'd') + "…\" (251 bytes)");
}

TEST(OneLine, EscapesOnlyWhatBreaksTheLine) {
  EXPECT_EQ(oneLine("scene.json: objects[0].name: \"a\\nb\""), "scene.json: objects[0].name: \"a\\nb\"");
  EXPECT_EQ(oneLine("first\nsecond\r\n\x1b[31m"), R"(first\nsecond\r\n\x1B[31m)");
  EXPECT_EQ(oneLine("±10000 m \xff"), R"(±10000 m \xFF)");
}

}  // namespace
}  // namespace omnicam
