// Daemons started in any order (the README's agent read listen.addr before radfarmd had
// written it and exited, and agents retried a restarted master's old port forever):
// radfarm-agent --master-file reads the master's listen.addr before every connection attempt, and
// radfarmd --detach returns only once the master is ready.
#include <signal.h>
#include <sys/stat.h>

#include <chrono>
#include <filesystem>
#include <string>

#include "tests/farm/farm_fixture.h"

namespace radfarm::testing {
namespace {

using std::chrono::seconds;

TEST_F(FarmTest, AnAgentWithAMasterFileWaitsForTheMasterAndFindsItAgainAfterARestart) {
  const std::string addr_file = farm_.state_dir() + "/listen.addr";
  ChildProcess agent({RADFARM_AGENT_PATH, "--master-file", addr_file, "--secret-file",
                      farm_.secret_file(), "--threads", "1", "--name", "follower"},
                     Path("follower.log"));
  // No master yet: the agent waits for the file instead of exiting.
  ASSERT_TRUE(WaitUntil([&] {
    return agent.Log().find("listen.addr: cannot open") != std::string::npos;
  })) << agent.Log();
  EXPECT_TRUE(agent.running()) << agent.Log();

  StartMaster();
  ASSERT_TRUE(farm_.WaitForAgents(1, seconds(60))) << agent.Log() << MasterLog();
  EXPECT_NE(agent.Log().find("names " + master_address()), std::string::npos) << agent.Log();

  // A restart on port 0 listens on another port (the old one is not reused at once); the agent
  // reads it from the new listen.addr.
  const std::string first = master_address();
  EXPECT_EQ(master().Stop(std::chrono::milliseconds(10000)), 0) << MasterLog();
  StartMaster();
  ASSERT_TRUE(farm_.WaitForAgents(1, seconds(60))) << agent.Log() << MasterLog();
  if (master_address() != first) {
    EXPECT_NE(agent.Log().find("names " + master_address()), std::string::npos) << agent.Log();
  }
  const int64_t id = Submit("cornell-box.toml", kShortJob);
  EXPECT_TRUE(WaitForState(id, "done"));
  EXPECT_EQ(agent.Stop(std::chrono::milliseconds(10000)), 0) << agent.Log();
}

TEST_F(FarmTest, AnAgentRefusesBothAMasterAndAMasterFile) {
  const CommandResult r = RunCommand({RADFARM_AGENT_PATH, "--master", "127.0.0.1:7878",
                                      "--master-file", "x", "--secret-file", farm_.secret_file()});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--master and --master-file: give one of them, not both"), std::string::npos)
      << r.err;
}

TEST_F(FarmTest, DetachReturnsOnceTheMasterIsReadyWithItsPid) {
  const std::string state = Path("detached");
  const CommandResult r = RunCommand({RADFARMD_PATH, "--detach", "--listen", "127.0.0.1:0",
                                      "--state-dir", state, "--secret-file", farm_.secret_file()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const pid_t pid = std::stoi(r.out);
  ASSERT_GT(pid, 0) << r.out;
  // Ready means usable at once: the address is written and the control socket answers.
  EXPECT_TRUE(std::filesystem::exists(state + "/listen.addr"));
  const CommandResult list =
      RunCommand({RADFARM_CLI_PATH, "--control", state + "/control.sock", "list"});
  EXPECT_EQ(list.exit_code, 0) << list.err;
  ASSERT_EQ(::kill(pid, SIGTERM), 0);
  EXPECT_TRUE(WaitUntil([&] { return ::kill(pid, 0) != 0; }, seconds(30)));
}

// Hostile neighbours: radfarmd started by hand under umask 022 made its state directory and
// store world-readable. They are its owner's alone whatever the umask.
TEST_F(FarmTest, AMasterStartedUnderUmask022KeepsItsStateAndStorePrivate) {
  const std::string state = Path("fresh/state");  // its parent is missing too
  const CommandResult r = RunCommand({"/bin/sh", "-c", "umask 022 && exec \"$@\"", "sh",
                                      RADFARMD_PATH, "--detach", "--listen", "127.0.0.1:0",
                                      "--state-dir", state, "--secret-file", farm_.secret_file()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const pid_t pid = std::stoi(r.out);
  ASSERT_GT(pid, 0) << r.out;
  const auto mode = [](const std::string& path) {
    struct stat st {};
    return ::stat(path.c_str(), &st) == 0 ? st.st_mode & 0777 : 01000u;
  };
  EXPECT_EQ(mode(Path("fresh")), 0700u);
  EXPECT_EQ(mode(state), 0700u);
  EXPECT_EQ(mode(state + "/radfarm.db"), 0600u);
  ASSERT_EQ(::kill(pid, SIGTERM), 0);
  EXPECT_TRUE(WaitUntil([&] { return ::kill(pid, 0) != 0; }, seconds(30)));
}

TEST_F(FarmTest, DetachReportsAMasterThatCannotStart) {
  const std::string bad_secret = Path("bad.secret");
  RunCommand({"/bin/sh", "-c", "echo not-hex > " + bad_secret});
  const CommandResult r = RunCommand({RADFARMD_PATH, "--detach", "--listen", "127.0.0.1:0",
                                      "--state-dir", Path("never"), "--secret-file", bad_secret});
  EXPECT_EQ(r.exit_code, 2) << r.err;  // the daemon's own exit code: bad secret
  EXPECT_EQ(r.out, "");
  EXPECT_NE(r.err.find("the daemon ended before it was ready"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace radfarm::testing
