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

// Pieces of every size around the 1 MiB buffer, streamed: the file is their concatenation.
TEST(AtomicFileTest, StreamedPiecesArriveWholeAndInOrder) {
  TestDir dir;
  const std::string path = dir.File("big.bin");
  Result<AtomicFileWriter> writer = AtomicFileWriter::Open(path);
  ASSERT_TRUE(writer.ok()) << writer.error();
  std::string expected;
  for (size_t size : {size_t{1}, size_t{1000}, size_t{1} << 20, size_t{3}, (size_t{1} << 20) - 1,
                      size_t{5} << 20, size_t{7}}) {
    std::string piece(size, '\0');
    for (size_t k = 0; k < size; ++k)
      piece[k] = static_cast<char>('a' + (k + expected.size()) % 26);
    ASSERT_TRUE(writer->Append(piece).ok());
    expected += piece;
  }
  EXPECT_EQ(dir.Entries().size(), 1u);  // the temporary, not yet the file
  ASSERT_TRUE(writer->Commit().ok());
  EXPECT_EQ(ReadFileBytes(path), expected);
  EXPECT_EQ(dir.Entries(), std::vector<std::string>{"big.bin"});
  EXPECT_FALSE(writer->Append("more").ok());
  EXPECT_FALSE(writer->Commit().ok());
}

// A writer given up on (an error while producing the contents) leaves the old file as it was.
TEST(AtomicFileTest, AbandonedWriterLeavesTheOldFileAndNoTemporary) {
  TestDir dir;
  const std::string path = dir.File("out.txt");
  ASSERT_TRUE(WriteFileAtomically(path, "old").ok());
  {
    Result<AtomicFileWriter> writer = AtomicFileWriter::Open(path);
    ASSERT_TRUE(writer.ok());
    ASSERT_TRUE(writer->Append(std::string(3 << 20, 'x')).ok());
    AtomicFileWriter moved(std::move(*writer));  // the moved-from writer must not delete it
    ASSERT_TRUE(moved.Append("y").ok());
  }
  EXPECT_EQ(ReadFileBytes(path), "old");
  EXPECT_EQ(dir.Entries(), std::vector<std::string>{"out.txt"});
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
