#include "testing/temp_dir.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace radfarm::testing {
namespace {

TEST(TempDirTest, MakesAFreshDirectoryAndRemovesItWithItsFiles) {
  std::string path;
  {
    const TempDir a("radfarm-temp-dir-test");
    const TempDir b("radfarm-temp-dir-test");
    path = a.path();
    EXPECT_NE(a.path(), b.path());
    EXPECT_TRUE(std::filesystem::is_directory(path));
    EXPECT_TRUE(std::filesystem::is_empty(path));
    EXPECT_NE(path.find("radfarm-temp-dir-test-"), std::string::npos);
    std::filesystem::create_directories(a.File("sub/dir"));
    std::ofstream(a.File("sub/dir/file")) << "x";
  }
  EXPECT_FALSE(std::filesystem::exists(path));
}

TEST(ReadFileTest, ReadsBytesAndGivesEmptyForAMissingFile) {
  const TempDir dir;
  std::ofstream(dir.File("f"), std::ios::binary) << std::string("a\0b\n", 4);
  EXPECT_EQ(ReadFile(dir.File("f")), std::string("a\0b\n", 4));
  EXPECT_EQ(ReadFile(dir.File("missing")), "");
}

}  // namespace
}  // namespace radfarm::testing
