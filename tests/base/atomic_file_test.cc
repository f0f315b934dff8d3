#include "base/atomic_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "tests/output/test_dir.h"

namespace radfarm {
namespace {

TEST(AtomicFileTest, WritesAndReplaces) {
  TestDir dir;
  const std::string path = dir.File("out.txt");
  ASSERT_TRUE(WriteFileAtomically(path, "first").ok());
  EXPECT_EQ(ReadFileBytes(path), "first");
  ASSERT_TRUE(WriteFileAtomically(path, std::string("sec\0nd", 6)).ok());
  EXPECT_EQ(ReadFileBytes(path), std::string("sec\0nd", 6));
  EXPECT_EQ(dir.Entries(), std::vector<std::string>{"out.txt"});
}

TEST(AtomicFileTest, MissingDirectoryNamesPathAndLeavesNothing) {
  TestDir dir;
  const std::string path = dir.File("missing/out.txt");
  const Status status = WriteFileAtomically(path, "x");
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.error().find(path), std::string::npos) << status.error();
  EXPECT_TRUE(dir.Entries().empty());
}

TEST(AtomicFileTest, RenameFailureLeavesNoTemporary) {
  TestDir dir;
  const std::string sub = dir.File("sub");
  ASSERT_TRUE(std::filesystem::create_directory(sub));
  // Renaming a file over a directory fails after the temporary was written.
  const Status status = WriteFileAtomically(sub, "x");
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.error().find(sub), std::string::npos) << status.error();
  EXPECT_EQ(dir.Entries(), std::vector<std::string>{"sub"});
}

TEST(AtomicFileTest, KnowsItsTemporaryNames) {
  EXPECT_TRUE(IsAtomicFileTemporary("abc.scene.tmp.123.4"));
  EXPECT_TRUE(IsAtomicFileTemporary("image.png.tmp.9.0"));
  EXPECT_FALSE(IsAtomicFileTemporary("abc.scene"));
  EXPECT_FALSE(IsAtomicFileTemporary(".tmp.1.2"));
  EXPECT_FALSE(IsAtomicFileTemporary("a.tmp.12"));
  EXPECT_FALSE(IsAtomicFileTemporary("a.tmp.1.2x"));
  EXPECT_FALSE(IsAtomicFileTemporary("a.tmp.1."));
}

TEST(AtomicFileTest, EmptyPathIsAnError) { EXPECT_FALSE(WriteFileAtomically("", "x").ok()); }

}  // namespace
}  // namespace radfarm
