// Results of the round in progress (schema version 6): accepted batch results are kept so that a
// restarted master leases again only what it had not received. They read back with the same
// bits, go with their round's checkpoint (in its transaction), and a damaged one is dropped, with
// a line naming it, so its batch is computed again.
#include <gtest/gtest.h>

#include "store/batch_result_codec.h"
#include "store/job_store.h"
#include "store/job_transactions.h"
#include "tests/store/flip_bit.h"
#include "tests/store/temp_dir.h"

namespace radfarm::store {
namespace {

StoredBatchResult Kept(uint32_t round, uint32_t index) {
  StoredBatchResult r;
  r.index = index;
  r.batch_rays = 4096;
  r.taper_ways = index % 2 == 0 ? 3000 : 0;  // kept with batch_rays, in its column's high bits
  r.batch = {round, 7 + index, uint64_t{index} * 4096, 4096};
  r.result.hits = {{3, 1000 + index}, {9, ~uint64_t{0} - index}, {4'000'000'000u, 1}};
  r.result.escaped_weight = 123456789012345ull + index;
  r.result.escaped_rays = 17;
  r.result.back_weight = 5;
  r.result.back_rays = 1;
  return r;
}

void ExpectSame(const StoredBatchResult& a, const StoredBatchResult& b) {
  EXPECT_EQ(a.index, b.index);
  EXPECT_EQ(a.batch_rays, b.batch_rays);
  EXPECT_EQ(a.taper_ways, b.taper_ways);
  EXPECT_EQ(a.batch.round, b.batch.round);
  EXPECT_EQ(a.batch.shooter, b.batch.shooter);
  EXPECT_EQ(a.batch.first_ray, b.batch.first_ray);
  EXPECT_EQ(a.batch.ray_count, b.batch.ray_count);
  EXPECT_TRUE(a.result == b.result);
}

Checkpoint CheckpointOfRound(JobId job, uint32_t round) {
  Checkpoint c;
  c.job = job;
  c.round = round;
  c.rounds_done = round + 1;
  c.radiosity = {Rgb(1, 2, 3)};
  c.unshot = {Rgb(0, 0, 0)};
  return c;
}

class RoundResultsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    path_ = dir_.File("radfarm.db");
    Reopen();
    ASSERT_TRUE(store_->PutScene("scene", std::vector<uint8_t>{1, 2, 3}).ok());
    job_ = *store_->SubmitJob({"job", "scene", "", 1, 0});
  }
  void Reopen() {
    store_.reset();
    Result<JobStore> store = JobStore::Open(path_);
    ASSERT_TRUE(store.ok()) << store.error();
    store_.emplace(std::move(*store));
  }
  void Save(std::vector<StoredBatchResult> results) {
    Status s = store_->SaveRoundResults(job_, results);
    ASSERT_TRUE(s.ok()) << s.error();
  }

  TempDir dir_;
  std::string path_;
  std::optional<JobStore> store_;
  JobId job_ = 0;
};

TEST_F(RoundResultsTest, ResultsReadBackWithTheSameBitsInRoundAndBatchOrder) {
  Save({Kept(4, 2), Kept(4, 0)});
  Save({Kept(3, 5), Kept(4, 1)});
  Save({Kept(4, 1)});  // stored again (a second master received it again): one row
  Reopen();
  Result<StoredRoundResults> all = store_->LoadRoundResults(job_, std::nullopt);
  ASSERT_TRUE(all.ok()) << all.error();
  EXPECT_TRUE(all->damaged.empty());
  ASSERT_EQ(all->results.size(), 4u);
  ExpectSame(all->results[0], Kept(3, 5));
  ExpectSame(all->results[1], Kept(4, 0));
  ExpectSame(all->results[2], Kept(4, 1));
  ExpectSame(all->results[3], Kept(4, 2));
  Result<StoredRoundResults> after = store_->LoadRoundResults(job_, 3);
  ASSERT_TRUE(after.ok());
  EXPECT_EQ(after->results.size(), 3u);
  EXPECT_EQ(*store_->CountRoundResults(job_, 4), 3);
  EXPECT_EQ(*store_->CountRoundResults(job_, 5), 0);
}

TEST_F(RoundResultsTest, PruningAfterARoundsCheckpointDeletesItsResultsAndThoseBefore) {
  Save({Kept(2, 0), Kept(3, 0), Kept(3, 1), Kept(4, 0)});
  ASSERT_TRUE(
      store_->SaveCheckpoint({job_, 3, 1, 100, 0.5, 1, 0.1}, CheckpointOfRound(job_, 3)).ok());
  // Left to PruneRoundResults, but a restart already reads only the round after the checkpoint.
  EXPECT_EQ(*store_->CountRoundResults(job_, 3), 2);
  Result<StoredRoundResults> after = store_->LoadRoundResults(job_, 3);
  ASSERT_TRUE(after.ok()) << after.error();
  ASSERT_EQ(after->results.size(), 1u);
  ExpectSame(after->results[0], Kept(4, 0));
  ASSERT_TRUE(store_->PruneRoundResults(job_, 3).ok());
  EXPECT_EQ(*store_->CountRoundResults(job_, 2), 0);
  EXPECT_EQ(*store_->CountRoundResults(job_, 3), 0);
  EXPECT_EQ(*store_->CountRoundResults(job_, 4), 1);
}

// A liar caught in round 4 whose first result was in round 4: only its results of round 4 go.
TEST_F(RoundResultsTest, RewindingToALiarsFirstRoundDeletesOnlyItsResultsThere) {
  ASSERT_TRUE(
      store_->SaveCheckpoint({job_, 3, 1, 100, 0.5, 1, 0.1}, CheckpointOfRound(job_, 3)).ok());
  Save({Kept(4, 0), Kept(4, 1), Kept(4, 2)});
  const std::vector<uint32_t> liars = {1};
  ASSERT_TRUE(store_->RewindJob(job_, 4, liars, false).ok());
  EXPECT_EQ(*store_->CountCheckpoints(job_), 1);
  Result<StoredRoundResults> kept = store_->LoadRoundResults(job_, 3);
  ASSERT_TRUE(kept.ok());
  ASSERT_EQ(kept->results.size(), 2u);
  ExpectSame(kept->results[0], Kept(4, 0));
  ExpectSame(kept->results[1], Kept(4, 2));
}

// A liar whose first result was in round 2, caught in round 4: the checkpoints of rounds 2 and 3
// held its results and go, and so does everything kept after round 2.
TEST_F(RoundResultsTest, RewindingPastACheckpointDeletesItAndEveryLaterResult) {
  for (uint32_t round : {1u, 2u, 3u}) {
    ASSERT_TRUE(
        store_->SaveCheckpoint({job_, round, 1, 100, 0.5, 1, 0.1}, CheckpointOfRound(job_, round))
            .ok());
  }
  Save({Kept(4, 0), Kept(4, 1)});
  ASSERT_TRUE(store_->RewindJob(job_, 2, {}, true).ok());
  EXPECT_EQ(*store_->CountCheckpoints(job_), 1);
  Result<std::optional<Checkpoint>> latest = store_->LoadLatestCheckpoint(job_);
  ASSERT_TRUE(latest.ok() && latest->has_value());
  EXPECT_EQ((*latest)->round, 1u);
  EXPECT_EQ(*store_->CountRoundResults(job_, 4), 0);
}

TEST_F(RoundResultsTest, ACheckpointThatFailsKeepsTheRoundsResults) {
  Save({Kept(3, 0)});
  // The checkpoint names a refined scene that is not stored: its row fails, and the transaction
  // rolls back as a whole.
  Checkpoint c = CheckpointOfRound(job_, 3);
  c.scene_hash = "not stored";
  EXPECT_FALSE(store_->SaveCheckpoint({job_, 3, 1, 100, 0.5, 1, 0.1}, c).ok());
  EXPECT_EQ(*store_->CountRoundResults(job_, 3), 1);
}

TEST_F(RoundResultsTest, ADamagedResultIsNamedDeletedAndTheOthersStillLoad) {
  Save({Kept(4, 0), Kept(4, 1), Kept(4, 2)});
  FlipBit(path_, "round_results", "result",
          "job_id = " + std::to_string(job_) + " AND round = 4 AND batch = 1");
  FlipBit(path_, "round_results", "checksum",
          "job_id = " + std::to_string(job_) + " AND round = 4 AND batch = 2");
  Reopen();
  Result<StoredRoundResults> loaded = store_->LoadRoundResults(job_, std::nullopt);
  ASSERT_TRUE(loaded.ok()) << loaded.error();
  ASSERT_EQ(loaded->results.size(), 1u);
  ExpectSame(loaded->results[0], Kept(4, 0));
  ASSERT_EQ(loaded->damaged.size(), 2u);
  EXPECT_NE(loaded->damaged[0].find("the stored result of job 1 round 4 batch 1 is damaged (its "
                                    "bytes do not match its checksum); it is computed again"),
            std::string::npos)
      << loaded->damaged[0];
  EXPECT_NE(loaded->damaged[1].find("round 4 batch 2 is damaged"), std::string::npos);
  // Deleted: the next load finds only the good one, and says nothing.
  Result<StoredRoundResults> again = store_->LoadRoundResults(job_, std::nullopt);
  ASSERT_TRUE(again.ok());
  EXPECT_EQ(again->results.size(), 1u);
  EXPECT_TRUE(again->damaged.empty());
}

TEST_F(RoundResultsTest, AJobStartsWithTheResultsAfterItsCheckpointAndWarnsOfDamagedOnes) {
  ASSERT_TRUE(
      store_->SaveCheckpoint({job_, 3, 1, 100, 0.5, 1, 0.1}, CheckpointOfRound(job_, 3)).ok());
  Save({Kept(4, 0), Kept(4, 1)});
  FlipBit(path_, "round_results", "result",
          "job_id = " + std::to_string(job_) + " AND round = 4 AND batch = 0");
  Result<std::vector<JobStart>> starts = StartQueuedJobs(*store_, 1);
  ASSERT_TRUE(starts.ok()) << starts.error();
  ASSERT_EQ(starts->size(), 1u);
  const JobStart& start = (*starts)[0];
  ASSERT_EQ(start.round_results.size(), 1u);
  ExpectSame(start.round_results[0], Kept(4, 1));
  ASSERT_EQ(start.warnings.size(), 1u);
  EXPECT_NE(start.warnings[0].find("round 4 batch 0 is damaged"), std::string::npos);
  Result<std::vector<Event>> events = store_->ListEvents(job_, 10);
  ASSERT_TRUE(events.ok());
  ASSERT_FALSE(events->empty());
  EXPECT_EQ(events->back().text, start.warnings[0]);
}

// A master killed after a checkpoint but before it pruned the round's results: the restart
// prunes them, as nothing reads them again.
TEST_F(RoundResultsTest, AJobStartDeletesTheResultsItsCheckpointLeftBehind) {
  Save({Kept(3, 0), Kept(3, 1), Kept(4, 0)});
  ASSERT_TRUE(
      store_->SaveCheckpoint({job_, 3, 1, 100, 0.5, 1, 0.1}, CheckpointOfRound(job_, 3)).ok());
  ASSERT_EQ(*store_->CountRoundResults(job_, 3), 2);
  Result<std::vector<JobStart>> starts = StartQueuedJobs(*store_, 1);
  ASSERT_TRUE(starts.ok()) << starts.error();
  ASSERT_EQ(starts->size(), 1u);
  ASSERT_EQ((*starts)[0].round_results.size(), 1u);
  ExpectSame((*starts)[0].round_results[0], Kept(4, 0));
  EXPECT_EQ(*store_->CountRoundResults(job_, 3), 0);
  EXPECT_EQ(*store_->CountRoundResults(job_, 4), 1);
}

TEST_F(RoundResultsTest, AFullStoreRefusesTheWriteAsAWhole) {
  store_.reset();
  JobStoreOptions options;
  options.max_pages = 1;  // SQLite keeps the file's size: every write that grows it fails
  Result<JobStore> capped = JobStore::Open(path_, options);
  ASSERT_TRUE(capped.ok()) << capped.error();
  std::vector<StoredBatchResult> many;
  for (uint32_t k = 0; k < 2000; ++k) many.push_back(Kept(0, k));
  Status s = capped->SaveRoundResults(job_, many);
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().find("SQLITE_FULL"), std::string::npos) << s.error();
  EXPECT_EQ(*capped->CountRoundResults(job_, 0), 0);
}

TEST(BatchResultCodecTest, EncodingRoundTripsAndBadBlobsAreRefused) {
  const BatchResult result = Kept(0, 1).result;
  const std::vector<uint8_t> blob = EncodeBatchResult(result);
  Result<BatchResult> back = DecodeBatchResult(blob);
  ASSERT_TRUE(back.ok()) << back.error();
  EXPECT_TRUE(*back == result);
  EXPECT_TRUE(DecodeBatchResult(EncodeBatchResult(BatchResult{})).ok());

  // Every shorter blob is refused, and so is one with a byte more.
  for (size_t n = 0; n < blob.size(); ++n) {
    EXPECT_FALSE(DecodeBatchResult(std::span(blob).first(n)).ok()) << n << " bytes";
  }
  std::vector<uint8_t> longer = blob;
  longer.push_back(0);
  EXPECT_FALSE(DecodeBatchResult(longer).ok());
  BatchResult unordered = result;
  std::swap(unordered.hits[0], unordered.hits[1]);
  Result<BatchResult> bad = DecodeBatchResult(EncodeBatchResult(unordered));
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().find("out of patch order"), std::string::npos) << bad.error();
  BatchResult repeated = result;
  repeated.hits[1].patch = repeated.hits[0].patch;
  EXPECT_FALSE(DecodeBatchResult(EncodeBatchResult(repeated)).ok());
  BatchResult zero = result;
  zero.hits[2].weight = 0;
  EXPECT_FALSE(DecodeBatchResult(EncodeBatchResult(zero)).ok());
  // A hit count the bytes cannot hold is refused before anything is allocated for it.
  const std::vector<uint8_t> huge_count = {'R',  'F',  'H',  '2',  0,    0,    0,    0,
                                           0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0x7f};
  EXPECT_FALSE(DecodeBatchResult(huge_count).ok());
  // A number over 64 bits.
  std::vector<uint8_t> overlong = {'R', 'F', 'H', '2'};
  overlong.insert(overlong.end(), 10, 0xff);
  overlong.push_back(0x01);
  EXPECT_FALSE(DecodeBatchResult(overlong).ok());
}

// The extremes of every field survive, and a batch of a big scene's patches (sorted ids a few
// hundred apart, weights 1 to 3: a shot's rays weigh 1 each) takes about a quarter of the bytes of
// fixed-width fields.
TEST(BatchResultCodecTest, ExtremesRoundTripAndTypicalHitsTakeAQuarterOfTheBytes) {
  BatchResult extremes;
  extremes.escaped_weight = UINT64_MAX;
  extremes.escaped_rays = 0;
  extremes.back_weight = uint64_t{1} << 63;
  extremes.back_rays = 127;
  extremes.hits = {{0, UINT64_MAX}, {1, 1}, {UINT32_MAX - 1, 128}, {UINT32_MAX, uint64_t{1} << 35}};
  Result<BatchResult> back = DecodeBatchResult(EncodeBatchResult(extremes));
  ASSERT_TRUE(back.ok()) << back.error();
  EXPECT_TRUE(*back == extremes);

  BatchResult typical;
  typical.escaped_rays = typical.escaped_weight = 3;
  uint32_t patch = 17;
  for (uint32_t k = 0; k < 3000; ++k) {
    typical.hits.push_back({patch, 1 + k % 3});
    patch += 1 + (k * 7919) % 400;
  }
  const std::vector<uint8_t> blob = EncodeBatchResult(typical);
  back = DecodeBatchResult(blob);
  ASSERT_TRUE(back.ok()) << back.error();
  EXPECT_TRUE(*back == typical);
  EXPECT_LT(blob.size() * 3, EncodeBatchResultFormat1(typical).size());
}

// Results an older master kept (fixed-width fields) are still read.
TEST(BatchResultCodecTest, FixedWidthBlobsOfAnOlderMasterStillDecode) {
  const BatchResult result = Kept(0, 1).result;
  const std::vector<uint8_t> old = EncodeBatchResultFormat1(result);
  EXPECT_EQ(old.size(), 40u + 12u * result.hits.size());
  Result<BatchResult> back = DecodeBatchResult(old);
  ASSERT_TRUE(back.ok()) << back.error();
  EXPECT_TRUE(*back == result);
  EXPECT_FALSE(DecodeBatchResult(std::span(old).first(old.size() - 1)).ok());
  EXPECT_FALSE(DecodeBatchResult(std::span(old).first(10)).ok());
  BatchResult unordered = result;
  std::swap(unordered.hits[0], unordered.hits[1]);
  EXPECT_FALSE(DecodeBatchResult(EncodeBatchResultFormat1(unordered)).ok());
}

// A job that ended is never resumed: its kept results go, whichever way it ended; those of jobs
// that may still run (queued, running, paused) stay.
TEST_F(RoundResultsTest, JobsThatEndedLoseTheirKeptResults) {
  std::vector<JobId> jobs = {job_};
  for (int k = 0; k < 5; ++k) jobs.push_back(*store_->SubmitJob({"job", "scene", "", 1, 0}));
  for (JobId job : jobs) ASSERT_TRUE(store_->SaveRoundResults(job, {{Kept(2, 0)}}).ok());
  const JobState states[] = {JobState::kQueued, JobState::kRunning, JobState::kPaused,
                             JobState::kDone,   JobState::kFailed,  JobState::kCancelled};
  for (size_t k = 1; k < jobs.size(); ++k) {
    ASSERT_TRUE(store_->SetJobState(jobs[k], JobState::kRunning).ok());
    if (states[k] != JobState::kRunning) {
      const std::optional<std::string> error =
          states[k] == JobState::kDone ? std::nullopt : std::optional<std::string>("stopped");
      ASSERT_TRUE(store_->SetJobState(jobs[k], states[k], error).ok()) << k;
    }
  }
  ASSERT_TRUE(store_->PruneEndedJobsRoundResults().ok());
  for (size_t k = 0; k < jobs.size(); ++k) {
    const bool ended = states[k] == JobState::kDone || states[k] == JobState::kFailed ||
                       states[k] == JobState::kCancelled;
    EXPECT_EQ(*store_->CountRoundResults(jobs[k], 2), ended ? 0 : 1) << JobStateName(states[k]);
  }
}

}  // namespace
}  // namespace radfarm::store
