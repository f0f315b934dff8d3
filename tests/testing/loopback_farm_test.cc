#include "testing/loopback_farm.h"

#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>

#include "testing/temp_dir.h"

namespace radfarm::testing {
namespace {

using std::chrono::seconds;

FarmPrograms Programs() { return {RADFARMD_PATH, RADFARM_AGENT_PATH, RADFARM_CLI_PATH}; }

TEST(LoopbackFarmTest, WritesAPrivateSecretBeforeAnythingStarts) {
  const TempDir dir;
  const LoopbackFarm farm(Programs(), dir.path());
  EXPECT_EQ(ReadFile(farm.secret_file()), farm.secret_hex() + "\n");
  EXPECT_EQ(farm.master(), nullptr);
  const auto perms = std::filesystem::status(farm.secret_file()).permissions();
  EXPECT_EQ(perms & std::filesystem::perms::group_read, std::filesystem::perms::none);
}

TEST(LoopbackFarmTest, MasterOnAnEphemeralPortAndAnAgentConnect) {
  const TempDir dir;
  LoopbackFarm farm(Programs(), dir.path());
  ChildProcess& master = farm.StartMaster({"--log-level", "debug"});
  ASSERT_TRUE(master.running()) << farm.MasterLog();
  ASSERT_FALSE(farm.master_address().empty());
  EXPECT_EQ(farm.master_address().rfind("127.0.0.1:", 0), 0u) << farm.master_address();
  EXPECT_NE(farm.master_address(), "127.0.0.1:0");
  farm.StartAgent("a", 1);
  EXPECT_TRUE(farm.WaitForAgents(1, seconds(60))) << farm.MasterLog();
  EXPECT_EQ(farm.Agents().size(), 1u);
  EXPECT_TRUE(farm.Status(12345).is_null());  // no such job: the CLI fails
  std::string error;
  EXPECT_EQ(farm.Submit(dir.File("missing.toml"), {}, &error), -1);
  EXPECT_NE(error.find("missing.toml"), std::string::npos) << error;
}

TEST(LoopbackFarmTest, AMasterThatExitsAtStartIsSeenAtOnce) {
  const TempDir dir;
  LoopbackFarm farm(Programs(), dir.path());
  // Bounded by the exit, not by the timeout: a test that hung here would time out in ctest.
  ChildProcess& master = farm.StartMaster({"--no-such-flag"}, std::chrono::seconds(600));
  EXPECT_FALSE(master.running());
  EXPECT_TRUE(farm.master_address().empty());
  EXPECT_FALSE(farm.MasterLog().empty());
}

TEST(IsFinishedTest, OnlyTheEndStates) {
  EXPECT_TRUE(IsFinished({{"state", "done"}}));
  EXPECT_TRUE(IsFinished({{"state", "failed"}}));
  EXPECT_TRUE(IsFinished({{"state", "cancelled"}}));
  EXPECT_FALSE(IsFinished({{"state", "running"}}));
  EXPECT_FALSE(IsFinished({{"state", "queued"}}));
  EXPECT_FALSE(IsFinished(nullptr));
}

}  // namespace
}  // namespace radfarm::testing
