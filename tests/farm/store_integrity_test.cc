// The job store against rot and faults, with a real radfarmd: a bit flipped
// in a stored checkpoint is noticed and the job recomputes from the checkpoint before, ending
// byte-identical to `radfarm render`; a full store holds a running job (`held`)
// instead of failing it, and the job resumes by itself once the store has room again.
#include <signal.h>

#include <filesystem>
#include <fstream>

#include "store/database.h"
#include "tests/farm/farm_fixture.h"

namespace radfarm::testing {
namespace {

// Flips one bit in the radiosity blob of the job's latest checkpoint, as rot on the disk would;
// returns that checkpoint's round, or -1.
int64_t FlipBitInLatestCheckpoint(const std::string& db_path, int64_t job) {
  Result<store::Database> db = store::Database::Open(db_path, {});
  if (!db) return -1;
  Result<store::Statement> read = db->Prepare(
      "SELECT round, radiosity FROM checkpoints WHERE job_id = ?1 ORDER BY round DESC LIMIT 1");
  if (!read) return -1;
  read->Bind(1, job);
  Result<bool> row = read->Step();
  if (!row || !*row) return -1;
  const int64_t round = read->Int(0);
  std::vector<uint8_t> bytes = read->Blob(1);
  bytes[bytes.size() / 3] ^= 0x04;
  Result<store::Statement> write =
      db->Prepare("UPDATE checkpoints SET radiosity = ?1 WHERE job_id = ?2 AND round = ?3");
  if (!write) return -1;
  write->BindBlob(1, bytes).Bind(2, job).Bind(3, round);
  return write->Run() ? round : -1;
}

std::string Port(const std::string& address) { return address.substr(address.rfind(':') + 1); }

TEST_F(FarmTest, ABitFlippedInAStoredCheckpointIsNoticedAndTheJobStillEndsLikeRender) {
  StartMaster();
  const std::string listen = "127.0.0.1:" + Port(master_address());
  StartAgent("slow", {"--slowdown", "3"});
  const int64_t id = Submit("cornell-box.toml");
  ASSERT_TRUE(WaitUntil([&] { return JobRound(Status(id)) >= 3; })) << MasterLog();
  // Paused, the job keeps its checkpoints and runs no round while its store is tampered with.
  ASSERT_EQ(Cli({"pause", std::to_string(id)}).exit_code, 0);
  master().Signal(SIGTERM);
  ASSERT_TRUE(master().WaitExit(std::chrono::seconds(60)).has_value());
  const int64_t damaged = FlipBitInLatestCheckpoint(Path("master/radfarm.db"), id);
  ASSERT_GE(damaged, 0);

  StartMaster({"--listen", listen});
  StartAgent("fast");
  ASSERT_EQ(Cli({"resume", std::to_string(id)}).exit_code, 0);
  ASSERT_TRUE(WaitForState(id, "done"));
  EXPECT_TRUE(FetchPatches(id) == ReferencePatches("cornell-box.toml"))
      << "the job resumed from damaged values";
  const std::string expected = "the checkpoint of job " + std::to_string(id) + " round " +
                               std::to_string(damaged) +
                               " is damaged (its bytes do not match its checksum)";
  EXPECT_EQ(CountLines(MasterLog(), expected), 1u) << MasterLog();
  const CommandResult log = Cli({"log", std::to_string(id)});
  EXPECT_NE(log.out.find(expected), std::string::npos) << log.out;
}

// F2: a 0-byte radfarm.db started as an empty store, every job gone, no warning.
TEST_F(FarmTest, RadfarmdRefusesAnEmptyStoreFileAndLeavesIt) {
  const std::string state = Path("empty-state");
  std::filesystem::create_directories(state);
  { std::ofstream(state + "/radfarm.db"); }
  const std::string secret = Path("empty-state-secret");
  ASSERT_EQ(RunCommand({RADFARM_CLI_PATH, "secret", "new", secret}).exit_code, 0);
  const CommandResult r = RunCommand(
      {RADFARMD_PATH, "--state-dir", state, "--secret-file", secret, "--listen", "127.0.0.1:0"});
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find(state + "/radfarm.db: the file is empty (0 bytes), not a job store"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(std::filesystem::file_size(state + "/radfarm.db"), 0u);
}

// F5: a brief disk-full turned running jobs `failed` and `resume` refused them. The store's size
// cap gives a real SQLITE_FULL: 128 KiB hold the schema and the submitted job, not a checkpoint.
TEST_F(FarmTest, AFullStoreHoldsTheJobAndItResumesByItselfOnceThereIsRoom) {
  StartMaster(
      {"--local-round-rays", "100000000", "--max-store-bytes", "128K", "--hold-retry-ms", "1000"});
  const std::string listen = "127.0.0.1:" + Port(master_address());
  const int64_t id = Submit("cornell-box.toml", kShortJob);
  ASSERT_TRUE(WaitForState(id, "held"));
  // The reason, from the job's log (the retry every second may already have released it again).
  const CommandResult log = Cli({"log", std::to_string(id)});
  EXPECT_NE(log.out.find("held: cannot save the checkpoint"), std::string::npos) << log.out;
  EXPECT_NE(log.out.find("SQLITE_FULL"), std::string::npos) << log.out;
  // Still full: each retry (and `resume`) runs the job again and holds it again; never failed.
  ASSERT_TRUE(WaitUntil([&] { return CountLines(MasterLog(), "released: the store") >= 1; }))
      << MasterLog();
  ASSERT_TRUE(WaitForState(id, "held"));
  EXPECT_NE(Status(id)["state"], "failed");
  EXPECT_TRUE(master().running());

  // Room again (the cap lifted): the held job goes back to the queue by itself and ends like
  // render, from the checkpoints it still had.
  master().Signal(SIGTERM);
  ASSERT_TRUE(master().WaitExit(std::chrono::seconds(60)).has_value());
  StartMaster({"--local-round-rays", "100000000", "--listen", listen, "--hold-retry-ms", "200"});
  ASSERT_TRUE(WaitForState(id, "done"));
  EXPECT_TRUE(FetchPatches(id) == ReferencePatches("cornell-box.toml", kShortJob));
}

}  // namespace
}  // namespace radfarm::testing
