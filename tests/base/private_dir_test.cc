// CreatePrivateDirectories and AtomicFileWriter's mode: a daemon started by hand under umask 022
// made its state world-readable.
#include "base/private_dir.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "base/atomic_file.h"

namespace radfarm {
namespace {

mode_t ModeOf(const std::string& path) {
  struct stat st {};
  EXPECT_EQ(stat(path.c_str(), &st), 0) << path;
  return st.st_mode & 0777;
}

// Sets the umask for one test and puts the old one back.
class Umask {
 public:
  explicit Umask(mode_t mask) : old_(umask(mask)) {}
  ~Umask() { umask(old_); }

 private:
  mode_t old_;
};

class PrivateDirTest : public ::testing::Test {
 protected:
  PrivateDirTest()
      : dir_(std::filesystem::temp_directory_path() /
             ("private-dir-test-" + std::to_string(getpid()))) {
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  ~PrivateDirTest() override { std::filesystem::remove_all(dir_); }
  std::string File(const std::string& name) const { return (dir_ / name).string(); }

  std::filesystem::path dir_;
};

TEST_F(PrivateDirTest, NewDirectoriesAreTheOwnersAloneWhateverTheUmask) {
  for (const mode_t mask : {mode_t{022}, mode_t{0}, mode_t{0277}}) {
    const Umask set(mask);
    const std::string leaf = File("m" + std::to_string(mask) + "/state/scenes");
    ASSERT_TRUE(CreatePrivateDirectories(leaf).ok());
    EXPECT_EQ(ModeOf(leaf), 0700u) << mask;
    EXPECT_EQ(ModeOf(File("m" + std::to_string(mask))), 0700u) << mask;
    EXPECT_TRUE(CreatePrivateDirectories(leaf).ok());  // already there
  }
}

TEST_F(PrivateDirTest, AnExistingDirectoryKeepsItsMode) {
  std::filesystem::create_directories(File("shared"));
  chmod(File("shared").c_str(), 0755);
  ASSERT_TRUE(CreatePrivateDirectories(File("shared")).ok());
  EXPECT_EQ(ModeOf(File("shared")), 0755u);
}

TEST_F(PrivateDirTest, AFileInTheWayIsNamed) {
  ASSERT_TRUE(WriteFileAtomically(File("file"), "x").ok());
  const Status s = CreatePrivateDirectories(File("file/below"));
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().find(File("file")), std::string::npos) << s.error();
}

TEST_F(PrivateDirTest, AnAtomicFileWithMode0600IsTheOwnersAloneUnderUmask022) {
  const Umask set(022);
  Result<AtomicFileWriter> writer = AtomicFileWriter::Open(File("private"), 0600);
  ASSERT_TRUE(writer.ok()) << writer.error();
  ASSERT_TRUE(writer->Append("secret").ok());
  ASSERT_TRUE(writer->Commit().ok());
  EXPECT_EQ(ModeOf(File("private")), 0600u);
  ASSERT_TRUE(WriteFileAtomically(File("ordinary"), "x").ok());
  EXPECT_EQ(ModeOf(File("ordinary")), 0644u);  // the default still follows the umask
}

}  // namespace
}  // namespace radfarm
