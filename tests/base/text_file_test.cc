#include "base/text_file.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

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

// /dev/zero and /dev/urandom never end, a FIFO blocks; only regular files are read.
TEST(ReadTextFileTest, RefusesWhatIsNotARegularFile) {
  Result<std::string> text = ReadTextFile("/dev/zero");
  ASSERT_FALSE(text.ok());
  EXPECT_EQ(text.error(), "/dev/zero: cannot open: not a regular file (a character device)");
  EXPECT_EQ(ReadTextFile("/").error(), "/: cannot open: is a directory");
}

TEST(ReadTextFileTest, RefusesAFileOverTheLimitFromItsSize) {
  const std::string path = ::testing::TempDir() + "/read_text_file_limit.txt";
  { std::ofstream(path) << "0123456789"; }
  EXPECT_EQ(*ReadTextFile(path, 10), "0123456789");
  Result<std::string> text = ReadTextFile(path, 9);
  ASSERT_FALSE(text.ok());
  EXPECT_EQ(text.error(), path + ": the file is 10 bytes, over the limit of 9 bytes");
  std::remove(path.c_str());
}

// /proc/self/status is a regular file whose size reads 0, yet holds hundreds of bytes: the limit
// holds for the bytes actually read, not for the size.
TEST(ReadTextFileTest, HoldsTheLimitOnTheBytesReadWhenTheSizeReadsZero) {
  const std::string path = "/proc/self/status";
  ASSERT_EQ(std::filesystem::file_size(path), 0u);
  Result<std::string> text = ReadTextFile(path, 16);
  ASSERT_FALSE(text.ok());
  EXPECT_EQ(text.error(), path + ": the file grew past the limit of 16 bytes while it was read");
  EXPECT_GT(ReadTextFile(path, 1 << 20)->size(), 16u);
}

}  // namespace
}  // namespace radfarm
