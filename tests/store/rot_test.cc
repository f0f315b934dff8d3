// The store notices rot: one bit flipped in a checkpoint passed `PRAGMA
// integrity_check`, the job read `done` and `fetch` returned a different solution without a word;
// a 0-byte radfarm.db started as an empty store, every job gone. Checksums (schema version 5) are
// verified on load: a damaged checkpoint gives way to the one before it, a damaged scene is an
// error, and an empty file is refused untouched.
#include <gtest/gtest.h>

#include "store/job_store.h"
#include "store/job_transactions.h"
#include "tests/store/flip_bit.h"
#include "tests/store/temp_dir.h"

namespace radfarm::store {
namespace {

Checkpoint Make(JobId job, uint32_t round) {
  Checkpoint c;
  c.job = job;
  c.round = round;
  c.rounds_done = round + 1;
  for (int i = 0; i < 4; ++i) {
    c.radiosity.push_back(Rgb(round + 1.0 / (i + 2), 0.5, 0.25));
    c.unshot.push_back(Rgb(1e-3 * i, 0, 0));
  }
  c.energy = {10.0, 6.0, 1.0, 3.0};
  return c;
}

class RotTest : public ::testing::Test {
 protected:
  void SetUp() override {
    path_ = dir_.File("radfarm.db");
    Reopen();
    ASSERT_TRUE(store_->PutScene("scene", std::vector<uint8_t>{1, 2, 3, 4}).ok());
    job_ = *store_->SubmitJob({"job", "scene", "", 1, 0});
    for (uint32_t round : {0u, 1u, 2u}) {
      const Checkpoint c = Make(job_, round);
      ASSERT_TRUE(store_->SaveCheckpoint({job_, round, 12, 1 << 16, 0.25, 3.0, 0.5}, c).ok());
    }
  }
  void Reopen() {
    store_.reset();
    Result<JobStore> store = JobStore::Open(path_);
    ASSERT_TRUE(store.ok()) << store.error();
    store_.emplace(std::move(*store));
  }

  TempDir dir_;
  std::string path_;
  std::optional<JobStore> store_;
  JobId job_ = 0;
};

TEST_F(RotTest, ABitFlippedInTheLatestCheckpointIsNoticedAndTheOneBeforeIsUsed) {
  FlipBit(path_, "checkpoints", "radiosity", "job_id = " + std::to_string(job_) + " AND round = 2");
  Reopen();
  // Without a list to report to, damage is an error naming the job and round.
  Result<std::optional<Checkpoint>> strict = store_->LoadLatestCheckpoint(job_);
  ASSERT_FALSE(strict.ok());
  EXPECT_NE(strict.error().find("the checkpoint of job 1 round 2 is damaged"), std::string::npos)
      << strict.error();
  std::vector<DamagedCheckpoint> damaged;
  Result<std::optional<Checkpoint>> fallback = store_->LoadLatestCheckpoint(job_, &damaged);
  ASSERT_TRUE(fallback.ok()) << fallback.error();
  ASSERT_TRUE(fallback->has_value());
  EXPECT_EQ((*fallback)->round, 1u);
  EXPECT_EQ((*fallback)->radiosity, Make(job_, 1).radiosity);
  ASSERT_EQ(damaged.size(), 1u);
  EXPECT_EQ(damaged[0].round, 2u);
}

TEST_F(RotTest, AJobStartingOverADamagedCheckpointResumesFromTheOneBeforeAndSaysSo) {
  FlipBit(path_, "checkpoints", "energy", "round = 2");
  Result<std::vector<JobStart>> starts = StartQueuedJobs(*store_, 1);
  ASSERT_TRUE(starts.ok()) << starts.error();
  ASSERT_EQ(starts->size(), 1u);
  const JobStart& start = starts->front();
  ASSERT_TRUE(start.checkpoint.has_value());
  EXPECT_EQ(start.checkpoint->round, 1u);
  ASSERT_EQ(start.warnings.size(), 1u);
  EXPECT_NE(start.warnings[0].find("round 2 is damaged"), std::string::npos) << start.warnings[0];
  EXPECT_NE(start.warnings[0].find("resuming from round 1"), std::string::npos);
  // The damaged row is gone, and the job's log says what happened.
  EXPECT_EQ(*store_->CountCheckpoints(job_), 2);
  const std::vector<Event> events = *store_->ListEvents(job_, 10);
  ASSERT_FALSE(events.empty());
  EXPECT_EQ(events.back().level, EventLevel::kWarning);
}

TEST_F(RotTest, AFinishedJobWithADamagedFinalCheckpointCannotBeFetchedAsAnOlderOne) {
  ASSERT_TRUE(store_->SetJobState(job_, JobState::kRunning).ok());
  ASSERT_TRUE(store_->SetJobState(job_, JobState::kDone).ok());
  FlipBit(path_, "checkpoints", "unshot", "round = 2");
  Result<std::optional<StoredSolution>> solution = LoadSolution(*store_, job_);
  ASSERT_FALSE(solution.ok());
  EXPECT_NE(solution.error().find("round 2 is damaged"), std::string::npos) << solution.error();
  EXPECT_NE(solution.error().find("the solution cannot be fetched"), std::string::npos);
}

TEST_F(RotTest, ADamagedSceneIsAnErrorNotOtherBytes) {
  FlipBit(path_, "scenes", "geometry", "hash = 'scene'");
  Result<std::optional<std::vector<uint8_t>>> scene = store_->GetScene("scene");
  ASSERT_FALSE(scene.ok());
  EXPECT_NE(scene.error().find("scene scene is damaged"), std::string::npos) << scene.error();
}

TEST(StoreFileTest, AnEmptyDatabaseFileIsRefusedAndLeftUntouched) {
  TempDir dir;
  const std::string path = dir.File("radfarm.db");
  WriteBytes(path, {});
  Result<JobStore> store = JobStore::Open(path);
  ASSERT_FALSE(store.ok());
  EXPECT_NE(store.error().find(path + ": the file is empty (0 bytes), not a job store"),
            std::string::npos)
      << store.error();
  EXPECT_TRUE(ReadBytes(path).empty());
}

TEST_F(RotTest, ABitFlippedInADisplayIsNoticedAndTheSolutionComesWithout) {
  ASSERT_TRUE(store_->PutDisplay(job_, 2, std::vector<uint8_t>(64, 0x5a)).ok());
  store_.reset();
  FlipBit(path_, "displays", "display", "job_id = " + std::to_string(job_));
  Reopen();
  Result<std::optional<StoredDisplay>> display = store_->GetDisplay(job_);
  ASSERT_FALSE(display.ok());
  EXPECT_NE(display.error().find("the display of job " + std::to_string(job_) + " is damaged"),
            std::string::npos)
      << display.error();
  // Fetch draws it again from the checkpoint: the same bits as the display that rotted.
  Result<std::optional<StoredSolution>> solution = LoadSolution(*store_, job_);
  ASSERT_TRUE(solution.ok() && solution->has_value()) << solution.error();
  EXPECT_TRUE((*solution)->display.empty());
}

}  // namespace
}  // namespace radfarm::store
