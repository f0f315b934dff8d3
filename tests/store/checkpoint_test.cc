// Rounds and checkpoints: bit-identical round trips, pruning, file size over a long job.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>

#include "store/job_store.h"
#include "tests/store/temp_dir.h"

namespace radfarm::store {
namespace {

class CheckpointTest : public ::testing::Test {
 protected:
  void SetUp() override {
    Result<JobStore> store = JobStore::Open(dir_.File("jobs.db"));
    ASSERT_TRUE(store.ok()) << store.error();
    store_.emplace(std::move(*store));
    ASSERT_TRUE(store_->PutScene("scene", std::vector<uint8_t>{1}).ok());
    job_ = *store_->SubmitJob({"job", "scene", "", 1, 0});
  }

  static Checkpoint Make(JobId job, uint32_t round, size_t patches) {
    Checkpoint checkpoint;
    checkpoint.job = job;
    checkpoint.round = round;
    checkpoint.rounds_done = round + 1;
    for (size_t i = 0; i < patches; ++i) {
      double x = (round + 1) * 1.0 / (i + 3.0);
      checkpoint.radiosity.push_back(Rgb(x, x * 0.5, x * 0.25));
      checkpoint.unshot.push_back(Rgb(x * 1e-3, 0, x * 1e-9));
    }
    checkpoint.energy = {10.0, 6.0 + round * 1e-3, 1.0, 3.0 - round * 1e-3};
    return checkpoint;
  }

  static RoundRecord RoundOf(const Checkpoint& checkpoint) {
    return {checkpoint.job, checkpoint.round, 12, 1 << 16, 0.25, 3.0, 0.5};
  }

  TempDir dir_;
  std::optional<JobStore> store_;
  JobId job_ = 0;
};

TEST_F(CheckpointTest, NoCheckpointIsNotAnError) {
  Result<std::optional<Checkpoint>> none = store_->LoadLatestCheckpoint(job_);
  ASSERT_TRUE(none.ok()) << none.error();
  EXPECT_FALSE(none->has_value());
}

TEST_F(CheckpointTest, EdgeValuesRoundTripBitIdentically) {
  const double denormal = std::numeric_limits<double>::denorm_min();
  Checkpoint checkpoint;
  checkpoint.job = job_;
  checkpoint.round = 7;
  checkpoint.rounds_done = 8;
  checkpoint.radiosity = {Rgb(0.0, -0.0, denormal), Rgb(1e308, -1e308, 2.2250738585072009e-308),
                          Rgb(std::numeric_limits<double>::max(), 0.1, 1.0 / 3.0)};
  checkpoint.unshot = {Rgb(-0.0, denormal * 3, 1e-300), Rgb(0, 0, 0), Rgb(1e308, 5e-324, 7)};
  // -0.0 in the energy too: a REAL column would give back +0.0.
  checkpoint.energy = {1e308, denormal, -0.0, 0.1 + 0.2};
  ASSERT_TRUE(store_->SaveCheckpoint(RoundOf(checkpoint), checkpoint).ok());

  Result<std::optional<Checkpoint>> back = store_->LoadLatestCheckpoint(job_);
  ASSERT_TRUE(back.ok() && back->has_value()) << back.error();
  const Checkpoint& loaded = **back;
  EXPECT_EQ(loaded.round, 7u);
  EXPECT_EQ(loaded.rounds_done, 8u);
  ASSERT_EQ(loaded.radiosity.size(), 3u);
  ASSERT_EQ(loaded.unshot.size(), 3u);
  EXPECT_EQ(std::memcmp(loaded.radiosity.data(), checkpoint.radiosity.data(), 3 * sizeof(Rgb)), 0);
  EXPECT_EQ(std::memcmp(loaded.unshot.data(), checkpoint.unshot.data(), 3 * sizeof(Rgb)), 0);
  EXPECT_EQ(std::memcmp(&loaded.energy, &checkpoint.energy, sizeof(EnergyAccount)), 0);
}

TEST_F(CheckpointTest, SavesRoundRowWithCheckpointAndLoadsLatest) {
  for (uint32_t round = 0; round < 5; ++round) {
    Checkpoint checkpoint = Make(job_, round, 10);
    ASSERT_TRUE(store_->SaveCheckpoint(RoundOf(checkpoint), checkpoint).ok());
  }
  ASSERT_TRUE(store_->RecordRound({job_, 5, 3, 100, 0.1, 1.0, 0.2, 7, 9}).ok());  // no checkpoint
  EXPECT_EQ(store_->ListRounds(job_)->size(), 6u);
  const RoundRecord fifth = store_->ListRounds(job_)->back();
  EXPECT_EQ(fifth.rays, 100u);
  EXPECT_EQ(fifth.escaped_rays, 7u);
  EXPECT_EQ(fifth.back_rays, 9u);
  Checkpoint latest = **store_->LoadLatestCheckpoint(job_);
  EXPECT_EQ(latest.round, 4u);
  EXPECT_EQ(latest.radiosity, Make(job_, 4, 10).radiosity);

  Checkpoint mismatched = Make(job_, 9, 2);
  mismatched.unshot.pop_back();
  EXPECT_FALSE(store_->SaveCheckpoint(RoundOf(mismatched), mismatched).ok());
  Checkpoint other_round = Make(job_, 9, 2);
  EXPECT_FALSE(store_->SaveCheckpoint({job_, 8, 1, 1, 0, 0, 0}, other_round).ok());
  Checkpoint no_job = Make(job_ + 99, 0, 2);
  Status orphan = store_->SaveCheckpoint(RoundOf(no_job), no_job);
  ASSERT_FALSE(orphan.ok());
  EXPECT_NE(orphan.error().find("SQLITE_CONSTRAINT"), std::string::npos) << orphan.error();
}

// The master logs it and restart_bench reads it: the bytes are the row's blobs and checksum.
TEST_F(CheckpointTest, SaveReportsWhatTheCheckpointCost) {
  const Checkpoint c = Make(job_, 0, 1000);
  CheckpointCost cost;
  cost.commit_seconds = -1;
  ASSERT_TRUE(store_->SaveCheckpoint(RoundOf(c), c, &cost).ok());
  EXPECT_EQ(cost.bytes, 2 * 24 * 1000u + 32 + 32);
  EXPECT_GE(cost.encode_seconds, 0);
  EXPECT_GE(cost.commit_seconds, 0);
}

// The key the web console caches a job's preview under: the latest checkpoint's round and time
// of writing, read without its arrays.
TEST_F(CheckpointTest, TheLatestStampIsTheHighestRoundsRoundAndTime) {
  EXPECT_FALSE(store_->LatestCheckpointStamp(job_)->has_value());
  for (uint32_t round : {2u, 7u, 5u}) {
    Checkpoint checkpoint = Make(job_, round, 4);
    ASSERT_TRUE(store_->SaveCheckpoint(RoundOf(checkpoint), checkpoint).ok());
  }
  const std::optional<std::pair<uint32_t, int64_t>> stamp = *store_->LatestCheckpointStamp(job_);
  ASSERT_TRUE(stamp.has_value());
  EXPECT_EQ(stamp->first, 7u);
  EXPECT_EQ(stamp->second, (*store_->LoadLatestCheckpoint(job_))->created_at_ms);
}

TEST_F(CheckpointTest, PruneKeepsExactlyTheLastK) {
  for (uint32_t round = 0; round < 10; ++round) {
    Checkpoint checkpoint = Make(job_, round, 4);
    ASSERT_TRUE(store_->SaveCheckpoint(RoundOf(checkpoint), checkpoint).ok());
  }
  JobId other = *store_->SubmitJob({"other", "scene", "", 1, 0});
  Checkpoint kept = Make(other, 0, 4);
  ASSERT_TRUE(store_->SaveCheckpoint(RoundOf(kept), kept).ok());

  ASSERT_TRUE(store_->PruneCheckpoints(job_, 3).ok());
  EXPECT_EQ(*store_->CountCheckpoints(job_), 3);
  EXPECT_EQ((*store_->LoadLatestCheckpoint(job_))->round, 9u);
  EXPECT_EQ(store_->ListRounds(job_)->size(), 10u);  // round rows stay
  EXPECT_EQ(*store_->CountCheckpoints(other), 1);    // other jobs untouched
  ASSERT_TRUE(store_->PruneCheckpoints(job_, 3).ok());
  EXPECT_EQ(*store_->CountCheckpoints(job_), 3);
  ASSERT_TRUE(store_->PruneCheckpoints(job_, 1).ok());
  EXPECT_EQ(*store_->CountCheckpoints(job_), 1);
  EXPECT_EQ((*store_->LoadLatestCheckpoint(job_))->round, 9u);
  ASSERT_TRUE(store_->PruneCheckpoints(job_, 0).ok());
  EXPECT_EQ(*store_->CountCheckpoints(job_), 0);
  EXPECT_FALSE(store_->PruneCheckpoints(job_, -1).ok());
}

// A long job: a checkpoint every round, pruned to the last 3. Freed pages are reused, so the file
// stays near a handful of checkpoints however many rounds run.
TEST_F(CheckpointTest, FileStaysSmallOver1000RoundsWithPruning) {
  const size_t patches = 2000;
  const int keep = 3;
  const uintmax_t checkpoint_bytes = 2 * patches * 24;
  for (uint32_t round = 0; round < 1000; ++round) {
    Checkpoint checkpoint = Make(job_, round, patches);
    ASSERT_TRUE(store_->SaveCheckpoint(RoundOf(checkpoint), checkpoint).ok());
    ASSERT_TRUE(store_->PruneCheckpoints(job_, keep).ok());
  }
  EXPECT_EQ(*store_->CountCheckpoints(job_), keep);
  uintmax_t file = std::filesystem::file_size(dir_.File("jobs.db"));
  uintmax_t wal = std::filesystem::file_size(dir_.File("jobs.db-wal"));
  std::printf(
      "1000 rounds, %zu patches (%ju bytes per checkpoint), keep %d: file %ju bytes, "
      "WAL %ju bytes\n",
      patches, checkpoint_bytes, keep, file, wal);
  EXPECT_LT(file, (keep + 3) * checkpoint_bytes);
  // The WAL is reset after each automatic checkpoint (1000 pages) and is not truncated.
  EXPECT_LT(wal, uintmax_t{6} << 20);
}

}  // namespace
}  // namespace radfarm::store
