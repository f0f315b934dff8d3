// Failures: rolled-back transactions, a full disk, I/O errors, a busy or unopenable file. Each
// surfaces as a Status error naming the SQLite code, and leaves nothing partial behind.
#include <gtest/gtest.h>
#include <sqlite3.h>

#include <cstdio>

#include "store/database.h"
#include "store/job_store.h"
#include "store/sqlite_error.h"
#include "tests/store/faulty_vfs.h"
#include "tests/store/temp_dir.h"

namespace radfarm::store {
namespace {

Checkpoint Make(JobId job, uint32_t round, size_t patches) {
  Checkpoint checkpoint;
  checkpoint.job = job;
  checkpoint.round = round;
  checkpoint.rounds_done = round + 1;
  checkpoint.radiosity.assign(patches, Rgb(round + 1.0, 0.5, 0.25));
  checkpoint.unshot.assign(patches, Rgb(1.0 / (round + 1), 0, 0));
  checkpoint.energy = {10, 5, 1, 4};
  return checkpoint;
}

RoundRecord RoundOf(const Checkpoint& checkpoint) {
  return {checkpoint.job, checkpoint.round, 4, 4096, 0.5, 2.0, 0.1};
}

// The message names the code, and the kind (what the master decides by) is the code's class.
void ExpectErrorNames(const Status& status, const std::string& code, ErrorKind kind) {
  ASSERT_FALSE(status.ok()) << "expected " << code;
  std::printf("failed as expected: %s\n", status.error().c_str());
  EXPECT_NE(status.error().find(code), std::string::npos) << status.error();
  EXPECT_EQ(status.error_kind(), kind) << status.error();
}

// Opens a store with one job, returning its id.
JobId OpenWithJob(const std::string& path, JobStoreOptions options, std::optional<JobStore>* out) {
  Result<JobStore> store = JobStore::Open(path, std::move(options));
  EXPECT_TRUE(store.ok()) << store.error();
  if (!store.ok()) return 0;
  out->emplace(std::move(*store));
  EXPECT_TRUE((*out)->PutScene("scene", std::vector<uint8_t>{1}).ok());
  return *(*out)->SubmitJob({"job", "scene", "", 1, 0});
}

int64_t Count(Database& db, const std::string& table) {
  return *db.QueryInt("SELECT count(*) FROM " + table);  // table names are this file's constants
}

TEST(TransactionTest, RollsBackUnlessCommitted) {
  TempDir dir;
  Result<Database> db = Database::Open(dir.File("t.db"), {});
  ASSERT_TRUE(db.ok());
  ASSERT_TRUE(db->Exec("CREATE TABLE t (x INTEGER NOT NULL)", "create").ok());
  {
    Result<Transaction> transaction = Transaction::Begin(*db);
    ASSERT_TRUE(transaction.ok());
    ASSERT_TRUE(db->Exec("INSERT INTO t VALUES (1)", "first insert").ok());
    // The injected failure mid-transaction: the caller returns early with its error.
    Status failed = db->Exec("INSERT INTO t VALUES (NULL)", "failing insert");
    ExpectErrorNames(failed, "SQLITE_CONSTRAINT", ErrorKind::kConstraint);
    EXPECT_TRUE(db->InTransaction());
  }
  EXPECT_FALSE(db->InTransaction());
  EXPECT_EQ(Count(*db, "t"), 0);
  {
    Result<Transaction> transaction = Transaction::Begin(*db);
    ASSERT_TRUE(db->Exec("INSERT INTO t VALUES (2)", "insert").ok());
    ASSERT_TRUE(transaction->Commit().ok());
    EXPECT_FALSE(transaction->Commit().ok());  // once only
  }
  EXPECT_EQ(Count(*db, "t"), 1);
}

// A trigger, added through a second connection, makes the checkpoint insert fail after the round
// row went in: neither may be visible afterwards.
TEST(FaultTest, SaveCheckpointIsAllOrNothing) {
  TempDir dir;
  std::string path = dir.File("jobs.db");
  std::optional<JobStore> store;
  JobId job = OpenWithJob(path, {}, &store);
  Checkpoint first = Make(job, 0, 8);
  ASSERT_TRUE(store->SaveCheckpoint(RoundOf(first), first).ok());

  Result<Database> other = Database::Open(path, {});
  ASSERT_TRUE(other.ok());
  ASSERT_TRUE(other
                  ->Exec("CREATE TRIGGER inject BEFORE INSERT ON checkpoints BEGIN"
                         " SELECT RAISE(ABORT, 'injected failure'); END",
                         "add trigger")
                  .ok());
  Checkpoint second = Make(job, 1, 8);
  // RAISE(ABORT) is SQLITE_CONSTRAINT_TRIGGER: a rule of the data, not a fault of the disk.
  ExpectErrorNames(store->SaveCheckpoint(RoundOf(second), second), "injected failure",
                   ErrorKind::kConstraint);
  EXPECT_EQ(store->ListRounds(job)->size(), 1u);  // round 1's row was rolled back
  EXPECT_EQ((*store->LoadLatestCheckpoint(job))->round, 0u);
  EXPECT_EQ(Count(*other, "rounds"), 1);

  ASSERT_TRUE(other->Exec("DROP TRIGGER inject", "drop trigger").ok());
  ASSERT_TRUE(store->SaveCheckpoint(RoundOf(second), second).ok());
  EXPECT_EQ((*store->LoadLatestCheckpoint(job))->round, 1u);
}

// PRAGMA max_page_count stands in for a full disk.
TEST(FaultTest, FullDiskIsAStatusAndLosesNothingCommitted) {
  TempDir dir;
  JobStoreOptions options;
  options.max_pages = 64;  // 256 KiB with 4 KiB pages
  std::optional<JobStore> store;
  JobId job = OpenWithJob(dir.File("jobs.db"), options, &store);
  Status status = Ok{};
  uint32_t round = 0;
  for (; round < 100; ++round) {
    Checkpoint checkpoint = Make(job, round, 1000);  // 48 KB per checkpoint
    status = store->SaveCheckpoint(RoundOf(checkpoint), checkpoint);
    if (!status.ok()) break;
  }
  ASSERT_GT(round, 0u);
  ExpectErrorNames(status, "SQLITE_FULL", ErrorKind::kDiskFull);
  EXPECT_TRUE(IsStoreFault(status.error_kind()));
  EXPECT_EQ((*store->LoadLatestCheckpoint(job))->round, round - 1);
  EXPECT_EQ(store->ListRounds(job)->size(), round);  // the failed round left no row
  // Pruning frees pages; the next checkpoint fits again.
  ASSERT_TRUE(store->PruneCheckpoints(job, 1).ok());
  Checkpoint retry = Make(job, round, 1000);
  EXPECT_TRUE(store->SaveCheckpoint(RoundOf(retry), retry).ok());
}

TEST(FaultTest, WriteErrorIsAStatusAndStoreRecovers) {
  RegisterFaultyVfs();
  TempDir dir;
  JobStoreOptions options;
  options.database.vfs = kFaultyVfsName;
  std::optional<JobStore> store;
  JobId job = OpenWithJob(dir.File("jobs.db"), options, &store);
  Checkpoint first = Make(job, 0, 100);
  ASSERT_TRUE(store->SaveCheckpoint(RoundOf(first), first).ok());
  Checkpoint second = Make(job, 1, 100);
  for (int writes_before_failure : {0, 1, 3}) {
    FaultyVfsArm arm(writes_before_failure);
    const Status failed = store->SaveCheckpoint(RoundOf(second), second);
    ExpectErrorNames(failed, "SQLITE_IOERR", ErrorKind::kIo);
    EXPECT_TRUE(IsStoreFault(failed.error_kind()));
    EXPECT_GT(arm.failures(), 0);
  }
  // Disarmed: what was committed is intact and writing works again.
  EXPECT_EQ((*store->LoadLatestCheckpoint(job))->round, 0u);
  EXPECT_EQ(store->ListRounds(job)->size(), 1u);
  ASSERT_TRUE(store->SaveCheckpoint(RoundOf(second), second).ok());
  EXPECT_EQ((*store->LoadLatestCheckpoint(job))->round, 1u);
}

TEST(FaultTest, DirectoryPathIsAnOpenError) {
  TempDir dir;
  Result<JobStore> store = JobStore::Open(dir.path().string());
  ASSERT_FALSE(store.ok());
  ExpectErrorNames(Error{store.error(), store.error_kind()}, "SQLITE_CANTOPEN", ErrorKind::kOther);
  Result<JobStore> missing = JobStore::Open(dir.File("no/such/dir/jobs.db"));
  ExpectErrorNames(Error{missing.error(), missing.error_kind()}, "SQLITE_CANTOPEN",
                   ErrorKind::kOther);
}

TEST(FaultTest, LockedDatabaseIsBusyAfterTheTimeout) {
  TempDir dir;
  std::string path = dir.File("jobs.db");
  JobStoreOptions options;
  options.database.busy_timeout_ms = 50;
  std::optional<JobStore> store;
  OpenWithJob(path, options, &store);
  Result<Database> other = Database::Open(path, {});
  ASSERT_TRUE(other.ok());
  Result<Transaction> held = Transaction::Begin(*other);  // another writer holds the lock
  ASSERT_TRUE(held.ok());
  Result<JobId> id = store->SubmitJob({"second", "scene", "", 1, 0});
  ASSERT_FALSE(id.ok());
  ExpectErrorNames(Error{id.error(), id.error_kind()}, "SQLITE_BUSY", ErrorKind::kBusy);
  EXPECT_FALSE(IsStoreFault(id.error_kind()));
  ASSERT_TRUE(held->Commit().ok());
  EXPECT_TRUE(store->SubmitJob({"second", "scene", "", 1, 0}).ok());
}

}  // namespace
}  // namespace radfarm::store
