#include "agent/file_user_idle.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "tests/agent/agent_process.h"

namespace radfarm::agent {
namespace {

using State = idle::UserIdle::State;
using testing::ScratchDir;
using testing::WriteTextFile;

TEST(FileUserIdleTest, ReadsIdleAndBusy) {
  ScratchDir dir;
  const std::string path = dir.File("user");
  FileUserIdle source(path);
  WriteTextFile(path, "busy\n");
  EXPECT_EQ(source.Read().state, State::kActive);
  WriteTextFile(path, "active");
  EXPECT_EQ(source.Read().state, State::kActive);
  WriteTextFile(path, "  idle \n");
  const idle::UserIdle idle = source.Read();
  EXPECT_EQ(idle.state, State::kIdle);
  EXPECT_GE(idle.idle_for.count(), 0);
}

TEST(FileUserIdleTest, IdleCountsFromTheFilesModificationTime) {
  ScratchDir dir;
  const std::string path = dir.File("user");
  WriteTextFile(path, "idle\n");
  std::filesystem::last_write_time(
      path, std::filesystem::file_time_type::clock::now() - std::chrono::hours(2));
  const idle::UserIdle idle = FileUserIdle(path).Read();
  EXPECT_EQ(idle.state, State::kIdle);
  // Two hours ago, give or take the time this test takes.
  EXPECT_GE(idle.idle_for, std::chrono::minutes(119));
  EXPECT_LE(idle.idle_for, std::chrono::minutes(180));
}

TEST(FileUserIdleTest, AMissingFileOrAnotherWordIsUnknownAndSaysWhy) {
  ScratchDir dir;
  const std::string path = dir.File("user");
  const idle::UserIdle missing = FileUserIdle(path).Read();
  EXPECT_EQ(missing.state, State::kUnknown);
  EXPECT_NE(missing.detail.find(path + ": cannot read"), std::string::npos) << missing.detail;
  WriteTextFile(path, "away\n");
  const idle::UserIdle other = FileUserIdle(path).Read();
  EXPECT_EQ(other.state, State::kUnknown);
  EXPECT_EQ(other.detail, path + ": expected 'idle' or 'busy', got 'away'");
  WriteTextFile(path, "");
  EXPECT_EQ(FileUserIdle(path).Read().state, State::kUnknown);
}

}  // namespace
}  // namespace radfarm::agent
