// `radfarm secret new`: a fresh hex secret the handshake can load, mode 0600, never replacing a
// file without --force, or on stdout with -.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>

#include "cli/exit_codes.h"
#include "protocol/farm_secret.h"
#include "testing/child_process.h"
#include "testing/temp_dir.h"

namespace radfarm {
namespace {

using testing::ReadFile;
using testing::RunCommand;
using testing::TempDir;

testing::CommandResult SecretNew(const std::vector<std::string>& args) {
  std::vector<std::string> full = {RADFARM_CLI_PATH, "secret", "new"};
  full.insert(full.end(), args.begin(), args.end());
  return RunCommand(full);
}

mode_t Mode(const std::string& path) {
  struct stat st {};
  EXPECT_EQ(stat(path.c_str(), &st), 0) << path;
  return st.st_mode & 07777;
}

size_t FilesIn(const std::string& dir) {
  size_t n = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir)) ++n;
  return n;
}

void ExpectLoadableSecret(const std::string& text) {
  ASSERT_EQ(text.size(), 65u) << text;  // 32 bytes as hex, and a newline
  EXPECT_EQ(text.back(), '\n');
  Result<protocol::FarmSecret> secret = protocol::FarmSecret::FromHex(text);
  ASSERT_TRUE(secret.ok()) << secret.error();
  EXPECT_EQ(secret->ToHex() + "\n", text);
}

TEST(SecretCommandTest, WritesAFreshSecretWithMode0600) {
  TempDir dir;
  const std::string file = dir.File("farm.key");
  const auto r = SecretNew({file});
  ASSERT_EQ(r.exit_code, kExitOk) << r.err;
  EXPECT_EQ(Mode(file), 0600u);
  ExpectLoadableSecret(ReadFile(file));
  EXPECT_EQ(FilesIn(dir.path()), 1u) << "a temporary file was left behind";
  const std::string other = dir.File("other.key");
  ASSERT_EQ(SecretNew({other}).exit_code, kExitOk);
  EXPECT_NE(ReadFile(file), ReadFile(other)) << "two secrets alike";
}

TEST(SecretCommandTest, RefusesToReplaceAFileWithoutForce) {
  TempDir dir;
  const std::string file = dir.File("farm.key");
  std::ofstream(file) << "precious\n";
  ASSERT_EQ(chmod(file.c_str(), 0644), 0);
  const auto refused = SecretNew({file});
  EXPECT_EQ(refused.exit_code, kExitBadInput);
  EXPECT_EQ(refused.err, "radfarm: " + file + ": already exists; pass --force to replace it\n");
  EXPECT_EQ(ReadFile(file), "precious\n");
  EXPECT_EQ(FilesIn(dir.path()), 1u);

  const auto forced = SecretNew({file, "--force"});
  ASSERT_EQ(forced.exit_code, kExitOk) << forced.err;
  ExpectLoadableSecret(ReadFile(file));
  EXPECT_EQ(Mode(file), 0600u) << "the replaced file's mode must not carry over";
  EXPECT_EQ(FilesIn(dir.path()), 1u);
}

TEST(SecretCommandTest, DashPrintsTheSecret) {
  TempDir dir;
  const auto r = RunCommand({RADFARM_CLI_PATH, "secret", "new", "-"});
  ASSERT_EQ(r.exit_code, kExitOk) << r.err;
  ExpectLoadableSecret(r.out);
  EXPECT_EQ(r.err, "");
}

// The README's `radfarm secret new /tmp/farm/secret` failed because /tmp/farm did not
// exist.
TEST(SecretCommandTest, MissingFoldersAreMadeWithMode0700) {
  TempDir dir;
  ::chmod(dir.path().c_str(), 0755);
  const auto r = SecretNew({dir.File("farm/keys/farm.key")});
  ASSERT_EQ(r.exit_code, kExitOk) << r.err;
  ExpectLoadableSecret(ReadFile(dir.File("farm/keys/farm.key")));
  EXPECT_EQ(Mode(dir.File("farm")), 0700u);
  EXPECT_EQ(Mode(dir.File("farm/keys")), 0700u);
  EXPECT_EQ(Mode(dir.File("farm/keys/farm.key")), 0600u);
  EXPECT_EQ(Mode(dir.path()), 0755u) << "a folder that exists is left as it is";
}

TEST(SecretCommandTest, AFolderThatCannotBeMadeFails) {
  TempDir dir;
  std::ofstream(dir.File("plain")) << "a file, not a folder\n";
  const auto r = SecretNew({dir.File("plain/farm/farm.key")});
  EXPECT_EQ(r.exit_code, kExitFailure);
  EXPECT_NE(r.err.find("plain/farm: cannot create the folder"), std::string::npos) << r.err;
}

TEST(SecretCommandTest, UsageErrors) {
  EXPECT_EQ(RunCommand({RADFARM_CLI_PATH, "secret"}).exit_code, kExitBadInput);
  EXPECT_EQ(SecretNew({}).exit_code, kExitBadInput);
  EXPECT_EQ(RunCommand({RADFARM_CLI_PATH, "secret", "old", "x"}).exit_code, kExitBadInput);
}

}  // namespace
}  // namespace radfarm
