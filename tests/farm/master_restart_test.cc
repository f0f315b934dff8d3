// A master restart keeps the round's work: radfarmd keeps each accepted batch result in
// its store until the round's checkpoint, so a master SIGKILLed mid-round and restarted leases
// again only the batches it had not received, and the job still ends byte-identical to `radfarm
// render`. A stored result damaged meanwhile is noticed, named in the log and computed again.
#include <signal.h>

#include <cstdio>
#include <regex>

#include "store/database.h"
#include "tests/farm/farm_fixture.h"
#include "tests/farm/kept_results.h"

namespace radfarm::testing {
namespace {

// Flips a bit in one stored result of `round`, as rot would; false when there is none.
bool DamageOneStoredResult(const std::string& db_path, int64_t job, int64_t round) {
  Result<store::Database> db = store::Database::Open(db_path, {});
  if (!db) return false;
  Result<store::Statement> read = db->Prepare(
      "SELECT batch, result FROM round_results WHERE job_id = ?1 AND round = ?2 LIMIT 1");
  if (!read) return false;
  read->Bind(1, job).Bind(2, round);
  Result<bool> row = read->Step();
  if (!row || !*row) return false;
  const int64_t batch = read->Int(0);
  std::vector<uint8_t> bytes = read->Blob(1);
  bytes[bytes.size() / 2] ^= 0x20;
  Result<store::Statement> write = db->Prepare(
      "UPDATE round_results SET result = ?1 WHERE job_id = ?2 AND round = ?3 AND batch = ?4");
  if (!write) return false;
  write->BindBlob(1, bytes).Bind(2, job).Bind(3, round).Bind(4, batch);
  return write->Run().ok();
}

std::string PortOf(const std::string& address) { return address.substr(address.rfind(':') + 1); }

TEST_F(FarmTest, AMasterKilledMidRoundLeasesOnlyTheBatchesItHadNotReceived) {
  StartMaster();
  const std::string listen = "127.0.0.1:" + PortOf(master_address());
  const std::string db = Path("master/radfarm.db");
  StartAgent("r1", {"--slowdown", "2"});
  StartAgent("r2", {"--slowdown", "2"});
  const int64_t id = Submit("cornell-box.toml");
  // A kill can land just after the round completed (its checkpoint deletes its results, and the
  // restart has none to use); kill again, a few times at most, until a restart used some.
  const std::regex restored_line(
      "round ([0-9]+): ([0-9]+) of ([0-9]+) batches restored from the store, ([0-9]+) to lease");
  // The numbers of the restart's "restored" line; round -1 until there is one. Every master
  // appends to the same log: only what the current one wrote (from `log_start`) counts.
  struct Restored {
    int64_t round = -1, got = 0, total = 0, to_lease = 0;
  } restored;
  size_t log_start = 0;
  const auto find_restored = [&] {
    const std::string log = MasterLog();
    if (log.size() <= log_start) return false;
    const std::string own = log.substr(log_start);
    std::smatch m;
    if (!std::regex_search(own, m, restored_line)) return false;
    restored = {std::stoll(m[1]), std::stoll(m[2]), std::stoll(m[3]), std::stoll(m[4])};
    return true;
  };
  constexpr int64_t kEnough = 6;
  // A kill that found nothing to use waits for a later round's results: the rows of the round it
  // landed after may still be in the store until the restart prunes them.
  int64_t used_up_round = -1;
  for (int kill = 0; kill < 5; ++kill) {
    ASSERT_TRUE(WaitUntil([&] {
      const KeptRound newest = NewestKeptRound(db, id);
      return (newest.round > used_up_round && newest.results >= kEnough) ||
             Status(id)["state"] == "done";
    })) << MasterLog();
    ASSERT_NE(Status(id)["state"], "done") << "the job ended before a round held enough results";
    master().Signal(SIGKILL);
    ASSERT_TRUE(master().WaitExit(std::chrono::seconds(30)).has_value());
    // Rot in one kept result while the master is down: it is dropped and its batch leased.
    const KeptRound kept = NewestKeptRound(db, id);
    const bool damaged = kept.results > 1 && DamageOneStoredResult(db, id, kept.round);
    std::printf("kill %d: round %lld held %lld results\n", kill + 1,
                static_cast<long long>(kept.round), static_cast<long long>(kept.results));
    log_start = MasterLog().size();
    StartMaster({"--listen", listen});
    // The restart logs its start before it plans: wait for the round to be leased or restored.
    ASSERT_TRUE(WaitUntil([&] {
      return find_restored() || JobRound(Status(id)) > kept.round || Status(id)["state"] == "done";
    })) << MasterLog();
    // A restored round is logged before it can end, but it may have ended (and the wait seen a
    // later round) between the log's read and the status (a slow build: `radfarm status` took
    // longer than the restored round's rest): read the log once more.
    if (restored.round < 0) find_restored();
    if (restored.round < 0) {
      used_up_round = kept.round;
      continue;
    }
    EXPECT_EQ(restored.round, kept.round + 1);  // the log numbers rounds from 1, the store from 0
    EXPECT_EQ(restored.got, kept.results - (damaged ? 1 : 0)) << MasterLog();
    EXPECT_LT(restored.to_lease, restored.total);
    EXPECT_EQ(restored.got + restored.to_lease, restored.total);
    if (damaged) {
      const std::regex damaged_line("the stored result of job " + std::to_string(id) + " round " +
                                    std::to_string(kept.round) +
                                    " batch [0-9]+ is damaged \\(its bytes do not match its "
                                    "checksum\\); it is computed again");
      const std::string log = MasterLog();
      EXPECT_TRUE(std::regex_search(log, damaged_line)) << log;
    }
    break;
  }
  ASSERT_GE(restored.round, 0) << "no restart found results to use\n" << MasterLog();
  ASSERT_TRUE(WaitForState(id, "done"));
  EXPECT_TRUE(FetchPatches(id) == ReferencePatches("cornell-box.toml"));
  // The last checkpoint took the kept results with it: the store does not grow.
  // Pruned after the job is done (JobRounds::FinishJob), so perhaps just after.
  EXPECT_TRUE(WaitUntil([&] { return KeptResults(Path("master/radfarm.db"), id) == 0; }));
}

// With rare checkpoints the rounds after the last one are not lost either: a restart replays them
// from their kept results, round by round, with the batches they had.
TEST_F(FarmTest, WithRareCheckpointsARestartReplaysTheRoundsSinceTheCheckpoint) {
  const std::vector<std::string> rare = {"--checkpoint-seconds", "100000"};
  StartMaster(rare);
  std::vector<std::string> again = rare;
  again.insert(again.end(), {"--listen", "127.0.0.1:" + PortOf(master_address())});
  StartAgent("p1");
  StartAgent("p2");
  const int64_t id = Submit("cornell-box.toml");
  // At most the first round is checkpointed before the job ends; wait for a few rounds.
  ASSERT_TRUE(WaitUntil([&] {
    const nlohmann::json job = Status(id);
    return JobRound(job) >= 4 || job["state"] == "done";
  })) << MasterLog();
  ASSERT_NE(Status(id)["state"], "done");
  master().Signal(SIGKILL);
  ASSERT_TRUE(master().WaitExit(std::chrono::seconds(30)).has_value());
  const int64_t kept = KeptResults(Path("master/radfarm.db"), id);
  StartMaster(again);
  ASSERT_TRUE(WaitForState(id, "done"));
  const std::string log = MasterLog();
  // The Cornell box leases rounds 0 and 1; the later ones are small enough for the master.
  EXPECT_GE(CountLines(log, "batches restored from the store"), 2u) << "kept " << kept << "\n"
                                                                    << log;
  EXPECT_TRUE(FetchPatches(id) == ReferencePatches("cornell-box.toml"));
  // Pruned after the job is done (JobRounds::FinishJob), so perhaps just after.
  EXPECT_TRUE(WaitUntil([&] { return KeptResults(Path("master/radfarm.db"), id) == 0; }));
}

}  // namespace
}  // namespace radfarm::testing
