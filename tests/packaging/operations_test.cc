// The procedures of docs/OPERATIONS.md, run against real radfarmd, radfarm-agent and radfarm
// processes on loopback (the tests/farm fixture): upgrading an agent while a job runs, and backing
// the job store up online and restoring it.
#include <signal.h>

#include <filesystem>

#include "tests/farm/farm_fixture.h"

namespace radfarm::testing {
namespace {

namespace fs = std::filesystem;

// The sqlite3 shell's path, or "" when it is not installed.
std::string Sqlite3() {
  const CommandResult found = RunCommand({"/bin/sh", "-c", "command -v sqlite3"});
  return found.exit_code == 0 ? found.out.substr(0, found.out.find('\n')) : "";
}

using OperationsTest = FarmTest;

// "Upgrade agents while a job runs": the package's try-restart sends SIGTERM; the agent hands its
// leases back and exits 0, the new one reconnects under the same name, and the job ends exactly
// as an undisturbed one.
TEST_F(OperationsTest, AnAgentRestartedForAnUpgradeMidJobChangesNothing) {
  StartMaster();
  ChildProcess& old_agent = StartAgent("render-07", {"--slowdown", "3"});
  const int64_t id = Submit("cornell-box.toml", kShortJob);
  ASSERT_TRUE(WaitUntil([&] { return AgentLeases(Agents(), "render-07") > 0; })) << MasterLog();

  old_agent.Signal(SIGTERM);
  const std::optional<int> exit_code = old_agent.WaitExit(std::chrono::seconds(60));
  ASSERT_TRUE(exit_code.has_value()) << "the agent did not stop on SIGTERM\n" << old_agent.Log();
  EXPECT_EQ(*exit_code, 0) << old_agent.Log();
  const nlohmann::json job = Status(id);
  EXPECT_TRUE(job["state"] == "running" || job["state"] == "done") << job.dump();

  StartAgent("render-07");  // the upgraded binary
  ASSERT_TRUE(WaitForState(id, "done"));
  EXPECT_TRUE(FetchPatches(id) == ReferencePatches("cornell-box.toml", kShortJob))
      << "the job's result changed";
}

// "Back up and restore the job store": sqlite3 .backup while radfarmd runs; the restored store
// (with the old WAL files removed) holds the job as it was and resumes it to the same result. The
// job is paused for the backup so that the test knows which state the backup holds.
TEST_F(OperationsTest, AnOnlineBackupRestoresAndTheJobResumesToTheSameResult) {
  const std::string sqlite3 = Sqlite3();
  if (sqlite3.empty()) GTEST_SKIP() << "sqlite3 is not installed (package sqlite3)";
  StartMaster();
  ChildProcess& agent = StartAgent("render-07", {"--slowdown", "3"});
  const int64_t id = Submit("cornell-box.toml", kShortJob);
  // Paused at once: the short job would otherwise be done before the backup.
  const CommandResult paused = Cli({"pause", std::to_string(id)});
  ASSERT_EQ(paused.exit_code, 0) << paused.err;
  ASSERT_TRUE(WaitForState(id, "paused"));
  const int64_t round_at_backup = JobRound(Status(id));

  const std::string db = farm_.state_dir() + "/radfarm.db";
  const std::string backup = Path("backup.db");
  const CommandResult backed_up = RunCommand({sqlite3, db, ".backup '" + backup + "'"});
  ASSERT_EQ(backed_up.exit_code, 0) << backed_up.err;
  const CommandResult check = RunCommand({sqlite3, backup, "PRAGMA integrity_check"});
  EXPECT_EQ(check.out, "ok\n") << check.err;

  // The job goes on and finishes; then the store is lost.
  ASSERT_EQ(Cli({"resume", std::to_string(id)}).exit_code, 0);
  ASSERT_TRUE(WaitForState(id, "done"));
  const std::string finished = FetchPatches(id);
  ASSERT_FALSE(finished.empty());
  agent.Signal(SIGTERM);
  master().Signal(SIGTERM);
  ASSERT_TRUE(master().WaitExit(std::chrono::seconds(60)).has_value()) << MasterLog();
  ASSERT_TRUE(agent.WaitExit(std::chrono::seconds(60)).has_value()) << agent.Log();
  for (const char* suffix : {"", "-wal", "-shm"}) fs::remove(db + suffix);
  fs::copy_file(backup, db);

  // Restored: the job is back as it was at the backup, and resumes to the same bits.
  StartMaster();
  const nlohmann::json restored = Status(id);
  ASSERT_TRUE(restored.is_object()) << MasterLog();
  EXPECT_EQ(restored["state"], "paused");
  EXPECT_EQ(JobRound(restored), round_at_backup);
  ASSERT_EQ(Cli({"resume", std::to_string(id)}).exit_code, 0);
  StartAgent("render-08");
  ASSERT_TRUE(WaitForState(id, "done"));
  EXPECT_TRUE(FetchPatches(id) == finished) << "the restored job ended differently";
}

}  // namespace
}  // namespace radfarm::testing
