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

TEST(CoreEditDistance, LevenshteinOfKnownPairs) {
  // The textbook pairs, counted by hand: kitten → sitting is two substitutions and an insertion.
  EXPECT_EQ(diffray::core::editDistance("kitten", "sitting"), 3u);
  EXPECT_EQ(diffray::core::editDistance("", "abc"), 3u);
  EXPECT_EQ(diffray::core::editDistance("ir", "ir"), 0u);
  EXPECT_EQ(diffray::core::editDistance("irr", "ir"), 1u);
  EXPECT_EQ(diffray::core::editDistance("rendr", "render"), 1u);
  EXPECT_EQ(diffray::core::editDistance("flaw", "lawn"), 2u);
}
