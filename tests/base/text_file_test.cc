#include "base/text_file.h"

#include <gtest/gtest.h>

#include <cmath>

namespace radfarm {
namespace {

TEST(SplitLinesTest, HonoursEveryLineBreakLikeTinyObjLoader) {
  auto lines = SplitLines("a\nb\r\nc\rd");
  ASSERT_EQ(lines.size(), 4u);
  EXPECT_EQ(lines[0], "a");
  EXPECT_EQ(lines[1], "b");
  EXPECT_EQ(lines[2], "c");
  EXPECT_EQ(lines[3], "d");
  EXPECT_EQ(SplitLines("a\n\nb\n").size(), 3u);  // the empty line still counts
}

TEST(SplitWordsTest, SplitsAtSpacesAndTabs) {
  auto words = SplitWords("  f\t1 2  3 ");
  ASSERT_EQ(words.size(), 4u);
  EXPECT_EQ(words[0], "f");
  EXPECT_EQ(words[3], "3");
}

TEST(BlankCommentsTest, KeepsLengthAndLineBreaks) {
  std::string text = "f 1 2 3 # note\n# whole\r\nv 1";
  const size_t size = text.size();
  BlankComments(&text);
  EXPECT_EQ(text.size(), size);
  EXPECT_EQ(SplitWords(SplitLines(text)[0]).size(), 4u);
  EXPECT_TRUE(SplitWords(SplitLines(text)[1]).empty());
  EXPECT_EQ(SplitLines(text)[2], "v 1");
}

TEST(ParseDoubleTest, AcceptsExporterFormsAndRejectsJunk) {
  double x = 0;
  EXPECT_TRUE(ParseDouble("+1.5", &x));
  EXPECT_EQ(x, 1.5);
  EXPECT_TRUE(ParseDouble(".5", &x));
  EXPECT_EQ(x, 0.5);
  EXPECT_TRUE(ParseDouble("-2e3", &x));
  EXPECT_EQ(x, -2000);
  EXPECT_TRUE(ParseDouble("1e999", &x));
  EXPECT_TRUE(std::isinf(x));
  EXPECT_FALSE(ParseDouble("abc", &x));
  EXPECT_FALSE(ParseDouble("1.5x", &x));
  EXPECT_FALSE(ParseDouble("", &x));
  EXPECT_FALSE(ParseDouble("+-1", &x));
}

TEST(ParseIntTest, WholeWordsOnly) {
  long long i = 0;
  EXPECT_TRUE(ParseInt("-7", &i));
  EXPECT_EQ(i, -7);
  EXPECT_TRUE(ParseInt("+7", &i));
  EXPECT_EQ(i, 7);
  EXPECT_FALSE(ParseInt("1.5", &i));
  EXPECT_FALSE(ParseInt("", &i));
  EXPECT_FALSE(ParseInt("99999999999999999999", &i));
}

TEST(ReadTextFileTest, NamesTheFileItCannotOpen) {
  Result<std::string> text = ReadTextFile("/nonexistent/file.obj");
  ASSERT_FALSE(text.ok());
  EXPECT_EQ(text.error(), "/nonexistent/file.obj: cannot open: No such file or directory");
  EXPECT_FALSE(ReadTextFile("/").ok());
}

}  // namespace
}  // namespace radfarm
