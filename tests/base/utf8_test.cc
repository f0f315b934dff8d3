#include "base/utf8.h"

#include <gtest/gtest.h>

namespace radfarm {
namespace {

TEST(Utf8Test, AcceptsAsciiAndWellFormedSequences) {
  EXPECT_EQ(FindInvalidUtf8(""), std::nullopt);
  EXPECT_EQ(FindInvalidUtf8("cornell-box.obj"), std::nullopt);
  EXPECT_EQ(FindInvalidUtf8("caf\xC3\xA9.obj"), std::nullopt);            // é
  EXPECT_EQ(FindInvalidUtf8("\xE2\x82\xAC"), std::nullopt);               // €
  EXPECT_EQ(FindInvalidUtf8("\xF0\x9F\x8F\xA0 house"), std::nullopt);     // U+1F3E0
  EXPECT_EQ(FindInvalidUtf8("\xEF\xBF\xBD"), std::nullopt);               // U+FFFD
  EXPECT_EQ(FindInvalidUtf8(std::string_view("a\0b", 3)), std::nullopt);  // NUL is UTF-8
}

// The bytes of the failures the fault campaign found: a Latin-1 scene name and 0xFF in a path.
TEST(Utf8Test, FindsTheFirstByteOutsideUtf8) {
  EXPECT_EQ(FindInvalidUtf8("caf\xE9.obj"), 3u);
  EXPECT_EQ(FindInvalidUtf8("scene\xFF"), 5u);
  EXPECT_EQ(FindInvalidUtf8("\xC3"), 0u);              // truncated
  EXPECT_EQ(FindInvalidUtf8("ok\xC0\xAF"), 2u);        // overlong '/'
  EXPECT_EQ(FindInvalidUtf8("\xE0\x80\xAF"), 0u);      // overlong
  EXPECT_EQ(FindInvalidUtf8("\xED\xA0\x80"), 0u);      // a surrogate
  EXPECT_EQ(FindInvalidUtf8("\xF4\x90\x80\x80"), 0u);  // above U+10FFFF
  EXPECT_EQ(FindInvalidUtf8("\xC3\xA9\xC3\x28"), 2u);  // bad continuation
  EXPECT_EQ(DescribeInvalidUtf8("caf\xE9", 3), "byte 0xE9 at offset 3");
}

}  // namespace
}  // namespace radfarm
