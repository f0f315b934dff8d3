// The store's named transactions (store/job_transactions.h, store/round_totals.h), each called
// directly on a temporary store: what the master's store thread runs for start, resume, operator
// commands, failures and fetch.
#include "store/job_transactions.h"

#include <gtest/gtest.h>
#include <sqlite3.h>

#include "store/round_totals.h"
#include "tests/store/temp_dir.h"

namespace radfarm::store {
namespace {

class JobTransactionsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    JobStoreOptions options;
    options.now_ms = clock_.Function();
    Result<JobStore> store = JobStore::Open(dir_.File("jobs.db"), options);
    ASSERT_TRUE(store.ok()) << store.error();
    store_.emplace(std::move(*store));
    ASSERT_TRUE(store_->PutScene("bundle", kBundle).ok());
  }

  JobId Submit(const std::string& name, int64_t priority = 0) {
    Result<JobId> id = store_->SubmitJob({name, "bundle", "{}", 7, priority});
    EXPECT_TRUE(id.ok()) << id.error();
    clock_.Advance(1);
    return id.ok() ? *id : 0;
  }

  JobState StateOf(JobId id) { return (*store_->GetJob(id))->state; }

  void Move(JobId id, JobState to) {
    std::optional<std::string> error;
    if (to == JobState::kFailed) error = "broken";
    Status s = store_->SetJobState(id, to, error);
    ASSERT_TRUE(s.ok()) << s.error();
  }

  // Round `round` with `rays` rays: one checkpoint row or one plain round row.
  static RoundRecord Round(JobId job, uint32_t round, uint64_t rays) {
    RoundRecord r{job, round, 3, rays, 0.5 / (round + 1), 1.0, 0.1 * (round + 1)};
    r.escaped_rays = rays / 4;
    r.back_rays = rays / 8;
    return r;
  }
  static Checkpoint CheckpointAt(JobId job, uint32_t round) {
    Checkpoint c;
    c.job = job;
    c.round = round;
    c.rounds_done = round + 1;
    c.radiosity = {Rgb(1, 2, 3), Rgb(0.5, 0.25, 0.125)};
    c.unshot = {Rgb(0.1, 0, 0), Rgb(0, 0, 0.2)};
    c.energy = {10, 6, 1, 3};
    return c;
  }
  void SaveCheckpoint(const Checkpoint& c, uint64_t rays = 1000) {
    Status s = store_->SaveCheckpoint(Round(c.job, c.round, rays), c);
    ASSERT_TRUE(s.ok()) << s.error();
  }

  // Runs `sql` on a second connection with foreign keys off: how a test takes a scene away.
  void RawSql(const std::string& sql) {
    sqlite3* db = nullptr;
    ASSERT_EQ(sqlite3_open(dir_.File("jobs.db").c_str(), &db), SQLITE_OK);
    char* message = nullptr;
    const int rc =
        sqlite3_exec(db, ("PRAGMA foreign_keys = OFF; " + sql).c_str(), nullptr, nullptr, &message);
    EXPECT_EQ(rc, SQLITE_OK) << (message ? message : "");
    sqlite3_free(message);
    sqlite3_close(db);
  }

  std::vector<std::string> EventsOf(JobId id) {
    std::vector<std::string> texts;
    Result<std::vector<Event>> events = store_->ListEvents(id, 100);
    EXPECT_TRUE(events.ok()) << events.error();
    if (events.ok()) {
      for (const Event& e : *events) texts.push_back(e.text);
    }
    return texts;
  }

  const std::vector<uint8_t> kBundle{1, 2, 3, 4};
  TempDir dir_;
  FakeClock clock_;
  std::optional<JobStore> store_;
};

// --- totals up to a round ---

TEST(RoundTotalsTest, SumsRowsUpToTheRoundAndStopsAtTheFirstLater) {
  const std::vector<RoundRecord> rounds = {
      {1, 0, 3, 100, 0.5, 1, 0.25, 10, 1},
      {1, 1, 3, 200, 0.25, 1, 0.5, 20, 2},
      {1, 2, 3, 400, 0.125, 1, 1.0, 40, 4},
  };
  const RoundTotals up_to_1 = TotalsUpToRound(rounds, 1);
  EXPECT_EQ(up_to_1.rounds, 2u);
  EXPECT_EQ(up_to_1.rays, 300u);
  EXPECT_EQ(up_to_1.escaped_rays, 30u);
  EXPECT_EQ(up_to_1.back_rays, 3u);
  EXPECT_EQ(up_to_1.seconds, 0.75);
  EXPECT_EQ(up_to_1.unshot_fraction, 0.25);
  EXPECT_EQ(TotalsUpToRound(rounds, 9).rays, 700u);
  const SolveTotals spent = up_to_1.solve_totals();
  EXPECT_EQ(spent.rays, 300u);
  EXPECT_EQ(spent.escaped_rays, 30u);
  EXPECT_EQ(spent.backface_hits, 3u);
  EXPECT_EQ(spent.seconds, 0.75);
}

TEST(RoundTotalsTest, NoRowsGiveZeroTotalsAndNoUnshotFraction) {
  const RoundTotals none = TotalsUpToRound({}, 5);
  EXPECT_EQ(none.rounds, 0u);
  EXPECT_EQ(none.rays, 0u);
  EXPECT_EQ(none.seconds, 0.0);
  EXPECT_FALSE(none.unshot_fraction.has_value());
}

TEST_F(JobTransactionsTest, TotalsOfStoredRoundsAddInRoundOrder) {
  const JobId job = Submit("totals");
  // Recorded out of order (a resume records rounds again): ListRounds gives them by round, and
  // the sum is the one an uninterrupted solve adds up, bit for bit.
  for (uint32_t round : {2u, 0u, 3u, 1u})
    ASSERT_TRUE(store_->RecordRound(Round(job, round, 7)).ok());
  const RoundTotals totals = TotalsUpToRound(*store_->ListRounds(job), 2);
  EXPECT_EQ(totals.rounds, 3u);
  EXPECT_EQ(totals.rays, 21u);
  EXPECT_EQ(totals.seconds, (0.1 * 1 + 0.1 * 2) + 0.1 * 3);
  EXPECT_EQ(totals.unshot_fraction, 0.5 / 3);
}

// --- start queued jobs ---

TEST_F(JobTransactionsTest, StartQueuedJobsMarksTheFirstByPriorityRunning) {
  const JobId low = Submit("low", 0);
  const JobId high = Submit("high", 5);
  const JobId third = Submit("third", 0);
  Result<std::vector<JobStart>> starts = StartQueuedJobs(*store_, 2);
  ASSERT_TRUE(starts.ok()) << starts.error();
  ASSERT_EQ(starts->size(), 2u);
  EXPECT_EQ((*starts)[0].record.id, high);
  EXPECT_EQ((*starts)[1].record.id, low);
  for (const JobStart& start : *starts) {
    EXPECT_EQ(start.record.state, JobState::kRunning);
    EXPECT_TRUE(start.record.started_at_ms.has_value());  // read after the change
    EXPECT_EQ(start.bundle, kBundle);
    EXPECT_FALSE(start.checkpoint.has_value());
    EXPECT_TRUE(start.rounds.empty());
  }
  EXPECT_EQ(StateOf(third), JobState::kQueued);
  Result<std::vector<JobStart>> rest = StartQueuedJobs(*store_, 5);
  ASSERT_TRUE(rest.ok()) << rest.error();
  ASSERT_EQ(rest->size(), 1u);
  EXPECT_EQ(rest->front().record.id, third);
  EXPECT_TRUE(StartQueuedJobs(*store_, 5)->empty());
}

TEST_F(JobTransactionsTest, StartQueuedJobsReadsWhatAResumeNeeds) {
  const JobId job = Submit("resumed");
  Move(job, JobState::kRunning);
  SaveCheckpoint(CheckpointAt(job, 0));
  ASSERT_TRUE(store_->PutScene("refined", std::vector<uint8_t>{9, 9}).ok());
  Checkpoint refined = CheckpointAt(job, 1);
  refined.scene_hash = "refined";
  SaveCheckpoint(refined);
  ASSERT_TRUE(store_->RecordRound(Round(job, 2, 50)).ok());  // after the checkpoint
  ASSERT_TRUE(RequeueRunningJobs(*store_).ok());

  Result<std::vector<JobStart>> starts = StartQueuedJobs(*store_, 1);
  ASSERT_TRUE(starts.ok()) << starts.error();
  ASSERT_EQ(starts->size(), 1u);
  const JobStart& start = starts->front();
  ASSERT_TRUE(start.checkpoint.has_value());
  EXPECT_EQ(start.checkpoint->round, 1u);
  EXPECT_EQ(start.checkpoint_scene, (std::vector<uint8_t>{9, 9}));
  EXPECT_EQ(start.rounds.size(), 3u);  // all of them: Prepare sums those up to the checkpoint
}

TEST_F(JobTransactionsTest, StartQueuedJobsLeavesAMissingRefinedSceneToTheCaller) {
  const JobId job = Submit("refined");
  Move(job, JobState::kRunning);
  ASSERT_TRUE(store_->PutScene("refined", std::vector<uint8_t>{9}).ok());
  Checkpoint c = CheckpointAt(job, 0);
  c.scene_hash = "refined";
  SaveCheckpoint(c);
  Move(job, JobState::kQueued);
  RawSql("DELETE FROM scenes WHERE hash = 'refined'");
  Result<std::vector<JobStart>> starts = StartQueuedJobs(*store_, 1);
  ASSERT_TRUE(starts.ok()) << starts.error();
  ASSERT_EQ(starts->size(), 1u);
  EXPECT_TRUE(starts->front().checkpoint->scene_hash.has_value());
  EXPECT_FALSE(starts->front().checkpoint_scene.has_value());
}

TEST_F(JobTransactionsTest, StartQueuedJobsFailsOnAMissingBundle) {
  const JobId job = Submit("orphan");
  RawSql("DELETE FROM scenes WHERE hash = 'bundle'");
  Result<std::vector<JobStart>> starts = StartQueuedJobs(*store_, 1);
  ASSERT_FALSE(starts.ok());
  EXPECT_EQ(starts.error(), "job " + std::to_string(job) + ": its scene is missing");
}

TEST_F(JobTransactionsTest, RequeueRunningJobsPutsOnlyRunningJobsBack) {
  const JobId running = Submit("running");
  const JobId paused = Submit("paused");
  const JobId done = Submit("done");
  Move(running, JobState::kRunning);
  Move(paused, JobState::kPaused);
  Move(done, JobState::kRunning);
  Move(done, JobState::kDone);
  Result<int> requeued = RequeueRunningJobs(*store_);
  ASSERT_TRUE(requeued.ok()) << requeued.error();
  EXPECT_EQ(*requeued, 1);
  EXPECT_EQ(StateOf(running), JobState::kQueued);
  EXPECT_EQ(StateOf(paused), JobState::kPaused);
  EXPECT_EQ(StateOf(done), JobState::kDone);
  EXPECT_EQ(EventsOf(running), std::vector<std::string>{
                                   "master restarted: the job resumes from its latest checkpoint"});
}

// --- change a job's state ---

TEST_F(JobTransactionsTest, PauseResumeAndCancelFollowTheRules) {
  const JobId job = Submit("job");
  Result<StateChange> paused = ChangeJobState(*store_, job, JobCommand::kPause);
  ASSERT_TRUE(paused.ok()) << paused.error();
  EXPECT_TRUE(paused->refused.empty());
  EXPECT_EQ(paused->job->state, JobState::kPaused);
  Result<StateChange> resumed = ChangeJobState(*store_, job, JobCommand::kResume);
  ASSERT_TRUE(resumed.ok()) << resumed.error();
  EXPECT_EQ(resumed->job->state, JobState::kQueued);
  Move(job, JobState::kRunning);
  Result<StateChange> cancelled = ChangeJobState(*store_, job, JobCommand::kCancel);
  ASSERT_TRUE(cancelled.ok()) << cancelled.error();
  EXPECT_EQ(cancelled->job->state, JobState::kCancelled);
  EXPECT_EQ(cancelled->job->error, "cancelled by the operator");
  EXPECT_TRUE(cancelled->job->finished_at_ms.has_value());
  EXPECT_EQ(EventsOf(job), (std::vector<std::string>{"paused", "resumed", "cancelled"}));
}

TEST_F(JobTransactionsTest, AnIllegalCommandIsRefusedWithTheJobsState) {
  const JobId job = Submit("job");
  Move(job, JobState::kRunning);
  Result<StateChange> resumed = ChangeJobState(*store_, job, JobCommand::kResume);
  ASSERT_TRUE(resumed.ok()) << resumed.error();
  EXPECT_EQ(resumed->refused, "job " + std::to_string(job) + " is running: it cannot be resumed");
  EXPECT_EQ(resumed->job->state, JobState::kRunning);  // as it was
  Move(job, JobState::kDone);
  Result<StateChange> paused = ChangeJobState(*store_, job, JobCommand::kPause);
  ASSERT_TRUE(paused.ok()) << paused.error();
  EXPECT_EQ(paused->refused, "job " + std::to_string(job) + " is done: it cannot be paused");
  EXPECT_EQ(StateOf(job), JobState::kDone);
  EXPECT_TRUE(EventsOf(job).empty());
}

TEST_F(JobTransactionsTest, CommandsOnEveryStateMatchTheTable) {
  using enum JobState;
  const struct {
    JobState from;
    bool cancel, pause, resume;
  } rules[] = {{kQueued, true, true, false},     {kRunning, true, true, false},
               {kPaused, true, false, true},     {kHeld, true, true, true},
               {kDone, false, false, false},     {kFailed, false, false, false},
               {kCancelled, false, false, false}};
  for (const auto& rule : rules) {
    SCOPED_TRACE(std::string(JobStateName(rule.from)));
    EXPECT_EQ(IsAllowedCommand(rule.from, JobCommand::kCancel), rule.cancel);
    EXPECT_EQ(IsAllowedCommand(rule.from, JobCommand::kPause), rule.pause);
    EXPECT_EQ(IsAllowedCommand(rule.from, JobCommand::kResume), rule.resume);
  }
}

TEST_F(JobTransactionsTest, ACommandOnAMissingJobFindsNoJob) {
  Result<StateChange> change = ChangeJobState(*store_, 42, JobCommand::kCancel);
  ASSERT_TRUE(change.ok()) << change.error();
  EXPECT_FALSE(change->job.has_value());
  EXPECT_TRUE(change->refused.empty());
}

TEST_F(JobTransactionsTest, FailJobLeavesFinishedAndMissingJobsAlone) {
  const JobId running = Submit("running");
  const JobId cancelled = Submit("cancelled");
  Move(running, JobState::kRunning);
  Move(cancelled, JobState::kCancelled);
  Result<bool> failed = FailJob(*store_, running, "mesh broke");
  ASSERT_TRUE(failed.ok()) << failed.error();
  EXPECT_TRUE(*failed);
  EXPECT_EQ(StateOf(running), JobState::kFailed);
  EXPECT_EQ((*store_->GetJob(running))->error, "mesh broke");
  EXPECT_FALSE(*FailJob(*store_, cancelled, "late"));
  EXPECT_EQ(StateOf(cancelled), JobState::kCancelled);
  EXPECT_FALSE(*FailJob(*store_, 42, "gone"));
}

// --- load a solution ---

TEST_F(JobTransactionsTest, LoadSolutionReadsTheLatestCheckpointWithItsTotals) {
  const JobId job = Submit("fetched");
  Move(job, JobState::kRunning);
  SaveCheckpoint(CheckpointAt(job, 0), 100);
  ASSERT_TRUE(store_->RecordRound(Round(job, 1, 200)).ok());
  SaveCheckpoint(CheckpointAt(job, 2), 400);
  ASSERT_TRUE(store_->RecordRound(Round(job, 3, 800)).ok());  // after the latest checkpoint
  Result<std::optional<StoredSolution>> loaded = LoadSolution(*store_, job);
  ASSERT_TRUE(loaded.ok()) << loaded.error();
  ASSERT_TRUE(loaded->has_value());
  const StoredSolution& s = **loaded;
  EXPECT_EQ(s.job.id, job);
  EXPECT_EQ(s.checkpoint.round, 2u);
  EXPECT_EQ(s.checkpoint.radiosity, CheckpointAt(job, 2).radiosity);
  EXPECT_EQ(s.bundle, kBundle);
  EXPECT_FALSE(s.refined_scene.has_value());
  EXPECT_EQ(s.totals.rounds, 3u);
  EXPECT_EQ(s.totals.rays, 700u);
  EXPECT_EQ(s.totals.unshot_fraction, 0.5 / 3);
}

TEST_F(JobTransactionsTest, LoadSolutionBringsTheRefinedScene) {
  const JobId job = Submit("refined");
  Move(job, JobState::kRunning);
  ASSERT_TRUE(store_->PutScene("refined", std::vector<uint8_t>{5, 6}).ok());
  Checkpoint c = CheckpointAt(job, 0);
  c.scene_hash = "refined";
  SaveCheckpoint(c);
  Result<std::optional<StoredSolution>> loaded = LoadSolution(*store_, job);
  ASSERT_TRUE(loaded.ok() && loaded->has_value()) << loaded.error();
  EXPECT_EQ((*loaded)->refined_scene, (std::vector<uint8_t>{5, 6}));
}

TEST_F(JobTransactionsTest, LoadSolutionBringsTheDisplayDrawnFromItsCheckpoint) {
  const JobId job = Submit("drawn");
  Move(job, JobState::kRunning);
  SaveCheckpoint(CheckpointAt(job, 0));
  SaveCheckpoint(CheckpointAt(job, 1));
  ASSERT_TRUE(store_->PutDisplay(job, 1, std::vector<uint8_t>{7, 8, 9}).ok());
  Result<std::optional<StoredSolution>> loaded = LoadSolution(*store_, job);
  ASSERT_TRUE(loaded.ok() && loaded->has_value()) << loaded.error();
  EXPECT_EQ((*loaded)->display, (std::vector<uint8_t>{7, 8, 9}));

  // Drawn from another round than the latest checkpoint's: not this solution's display.
  ASSERT_TRUE(store_->PutDisplay(job, 0, std::vector<uint8_t>{1}).ok());
  loaded = LoadSolution(*store_, job);
  ASSERT_TRUE(loaded.ok() && loaded->has_value()) << loaded.error();
  EXPECT_TRUE((*loaded)->display.empty());
}

TEST_F(JobTransactionsTest, LoadSolutionWithoutACheckpointIsEmpty) {
  const JobId job = Submit("young");
  Result<std::optional<StoredSolution>> loaded = LoadSolution(*store_, job);
  ASSERT_TRUE(loaded.ok()) << loaded.error();
  EXPECT_FALSE(loaded->has_value());
}

TEST_F(JobTransactionsTest, LoadSolutionErrors) {
  Result<std::optional<StoredSolution>> none = LoadSolution(*store_, 42);
  ASSERT_FALSE(none.ok());
  EXPECT_EQ(none.error(), "no job 42");

  const JobId job = Submit("refined");
  Move(job, JobState::kRunning);
  ASSERT_TRUE(store_->PutScene("refined", std::vector<uint8_t>{5}).ok());
  Checkpoint c = CheckpointAt(job, 0);
  c.scene_hash = "refined";
  SaveCheckpoint(c);
  RawSql("DELETE FROM scenes WHERE hash = 'refined'");
  Result<std::optional<StoredSolution>> no_refined = LoadSolution(*store_, job);
  ASSERT_FALSE(no_refined.ok());
  EXPECT_EQ(no_refined.error(), "job " + std::to_string(job) + ": refined scene refined missing");
  RawSql("DELETE FROM scenes WHERE hash = 'bundle'");
  Result<std::optional<StoredSolution>> no_bundle = LoadSolution(*store_, job);
  ASSERT_FALSE(no_bundle.ok());
  EXPECT_EQ(no_bundle.error(), "job " + std::to_string(job) + ": scene missing");
}

// --- holds after store faults ---

TEST_F(JobTransactionsTest, HoldJobMakesARunningJobHeldWithItsReason) {
  const JobId job = Submit("job");
  Move(job, JobState::kRunning);
  ASSERT_TRUE(HoldJob(*store_, job, "cannot save the checkpoint: SQLITE_FULL").ok());
  const JobRecord held = **store_->GetJob(job);
  EXPECT_EQ(held.state, JobState::kHeld);
  EXPECT_EQ(held.error, "cannot save the checkpoint: SQLITE_FULL");
  EXPECT_EQ(EventsOf(job),
            std::vector<std::string>{"held: cannot save the checkpoint: SQLITE_FULL"});
  // Not a job to start: only the release or an operator queues it again.
  EXPECT_TRUE(StartQueuedJobs(*store_, 4)->empty());
}

TEST_F(JobTransactionsTest, ReleaseHeldJobsQueuesHeldAndUnrecordedJobsOnly) {
  const JobId held = Submit("held");
  const JobId paused = Submit("paused");
  const JobId unrecorded = Submit("unrecorded");
  const JobId running = Submit("running");
  for (JobId id : {held, unrecorded, running}) Move(id, JobState::kRunning);
  ASSERT_TRUE(HoldJob(*store_, held, "disk full").ok());
  // An operator's pause with a reason that reads like a hold stays an operator's pause.
  ASSERT_TRUE(store_->SetJobState(paused, JobState::kPaused, "held: by hand").ok());
  Result<std::vector<JobId>> released = ReleaseHeldJobs(*store_, {unrecorded});
  ASSERT_TRUE(released.ok()) << released.error();
  EXPECT_EQ(*released, (std::vector<JobId>{held, unrecorded}));
  EXPECT_EQ(StateOf(held), JobState::kQueued);
  EXPECT_FALSE((*store_->GetJob(held))->error.has_value());
  EXPECT_EQ(StateOf(unrecorded), JobState::kQueued);
  EXPECT_EQ(StateOf(paused), JobState::kPaused);
  EXPECT_EQ(StateOf(running), JobState::kRunning);
}

TEST_F(JobTransactionsTest, AHeldJobResumesLikeAPausedOneAndAPauseKeepsItFromRelease) {
  const JobId job = Submit("job");
  Move(job, JobState::kRunning);
  ASSERT_TRUE(HoldJob(*store_, job, "disk full").ok());
  Result<StateChange> resumed = ChangeJobState(*store_, job, JobCommand::kResume);
  ASSERT_TRUE(resumed.ok()) << resumed.error();
  EXPECT_TRUE(resumed->refused.empty()) << resumed->refused;
  EXPECT_EQ(resumed->job->state, JobState::kQueued);

  Move(job, JobState::kRunning);
  ASSERT_TRUE(HoldJob(*store_, job, "disk full").ok());
  Result<StateChange> paused = ChangeJobState(*store_, job, JobCommand::kPause);
  ASSERT_TRUE(paused.ok()) << paused.error();
  EXPECT_EQ(paused->job->state, JobState::kPaused);
  Result<std::vector<JobId>> released = ReleaseHeldJobs(*store_, {});
  ASSERT_TRUE(released.ok()) << released.error();
  EXPECT_TRUE(released->empty());
  EXPECT_EQ(StateOf(job), JobState::kPaused);
}

}  // namespace
}  // namespace radfarm::store
