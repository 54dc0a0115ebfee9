// clipForMessage (mddual/error.h): how a user's text appears in a message.
#include <gtest/gtest.h>

#include <string>

#include "mddual/error.h"

namespace mddual {
namespace {

TEST(ClipForMessage, ControlBytesAreShownAsQuestionMarks) {
  EXPECT_EQ(clipForMessage(std::string("a\0b\nc\x1b[31m\x7f", 11)), "a?b?c?[31m?");
  EXPECT_EQ(clipForMessage("plain text"), "plain text");
}

TEST(ClipForMessage, LongTextIsCutAtACharacterBoundary) {
  EXPECT_EQ(clipForMessage(std::string(300, 'x')), std::string(200, 'x') + "... (300 bytes)");
  // 100 euro signs of 3 bytes: 200 bytes would end inside the 67th; the cut
  // steps back to its start (a split character made Python's message empty).
  std::string euros;
  for (int i = 0; i < 100; ++i) euros += "\xe2\x82\xac";
  std::string expected;
  for (int i = 0; i < 66; ++i) expected += "\xe2\x82\xac";
  EXPECT_EQ(clipForMessage(euros), expected + "... (300 bytes)");
  EXPECT_EQ(clipForMessage(euros, std::string::npos), euros);  // not cut: names, paths
  EXPECT_EQ(clipForMessage(std::string(200, 'x')), std::string(200, 'x'));
}

}  // namespace
}  // namespace mddual
