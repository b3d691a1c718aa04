// core::oneLine, which keeps errors and warnings that quote file names on one terminal line: control
// characters become visible escapes, everything else (UTF-8 included) passes unchanged. Oracle: literal
// expected strings.
#include <gtest/gtest.h>

#include <string>

#include "diffray/core/error.h"

namespace {

TEST(CoreOneLine, ControlCharactersBecomeEscapesAndTheRestIsKept) {
  using diffray::core::oneLine;
  EXPECT_EQ(oneLine("plain text, 3 ° é"), "plain text, 3 ° é");
  EXPECT_EQ(oneLine("a\nb\tc"), "a\\nb\\tc");
  EXPECT_EQ(oneLine(std::string("x\x1b[31my\x7f", 8)), "x\\x1b[31my\\x7f");
  EXPECT_EQ(oneLine(std::string("\r\x01", 2)), "\\x0d\\x01");
  EXPECT_EQ(oneLine(""), "");
}

}  // namespace
