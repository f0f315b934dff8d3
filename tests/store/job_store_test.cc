// Jobs, their states and order, scenes, agents and events.
#include "store/job_store.h"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include "tests/store/temp_dir.h"

namespace radfarm::store {
namespace {

class JobStoreTest : public ::testing::Test {
 protected:
  void SetUp() override {
    JobStoreOptions options;
    options.now_ms = clock_.Function();
    Result<JobStore> store = JobStore::Open(dir_.File("jobs.db"), options);
    ASSERT_TRUE(store.ok()) << store.error();
    store_.emplace(std::move(*store));
    ASSERT_TRUE(store_->PutScene("scene", std::vector<uint8_t>{1, 2, 3}).ok());
  }

  JobId Submit(const std::string& name, int64_t priority) {
    Result<JobId> id = store_->SubmitJob({name, "scene", "tolerance = 1e-3", 7, priority});
    EXPECT_TRUE(id.ok()) << id.error();
    return id.ok() ? *id : 0;
  }

  JobState StateOf(JobId id) { return (*store_->GetJob(id))->state; }

  TempDir dir_;
  FakeClock clock_;
  std::optional<JobStore> store_;
};

TEST_F(JobStoreTest, SubmitAndGetJob) {
  JobId id = Submit("cornell", 3);
  Result<std::optional<JobRecord>> job = store_->GetJob(id);
  ASSERT_TRUE(job.ok() && job->has_value());
  EXPECT_EQ((*job)->spec.name, "cornell");
  EXPECT_EQ((*job)->spec.scene_hash, "scene");
  EXPECT_EQ((*job)->spec.settings, "tolerance = 1e-3");
  EXPECT_EQ((*job)->spec.priority, 3);
  EXPECT_EQ((*job)->state, JobState::kQueued);
  EXPECT_EQ((*job)->submitted_at_ms, *clock_.now);
  EXPECT_FALSE((*job)->started_at_ms.has_value());
  EXPECT_FALSE(store_->GetJob(id + 100)->has_value());
  EXPECT_EQ(store_->ListJobs()->size(), 1u);
}

// A master started by hand under umask 022 left radfarm.db world-readable.
TEST(JobStoreFileTest, ANewStoreIsPrivateWhateverTheUmask) {
  TempDir dir;
  const mode_t old = umask(022);
  Result<JobStore> store = JobStore::Open(dir.File("jobs.db"), {});
  const bool put = store.ok() && store->PutScene("scene", std::vector<uint8_t>{1, 2, 3}).ok();
  umask(old);
  ASSERT_TRUE(store.ok()) << store.error();
  ASSERT_TRUE(put);
  for (const char* file : {"jobs.db", "jobs.db-wal"}) {
    struct stat st {};
    if (stat(dir.File(file).c_str(), &st) != 0) continue;  // no WAL in this journal mode
    EXPECT_EQ(st.st_mode & 0777, 0600u) << file;
  }
  struct stat db {};
  ASSERT_EQ(stat(dir.File("jobs.db").c_str(), &db), 0);
}

TEST_F(JobStoreTest, SeedKeepsAll64Bits) {
  Result<JobId> id = store_->SubmitJob({"big seed", "scene", "", ~uint64_t{0} - 5, 0});
  ASSERT_TRUE(id.ok());
  EXPECT_EQ((*store_->GetJob(*id))->spec.seed, ~uint64_t{0} - 5);
}

TEST_F(JobStoreTest, SubmitNeedsStoredScene) {
  Result<JobId> id = store_->SubmitJob({"orphan", "no-such-scene", "", 1, 0});
  ASSERT_FALSE(id.ok());
  EXPECT_NE(id.error().find("PutScene first"), std::string::npos) << id.error();
}

TEST_F(JobStoreTest, LifecycleSetsTimesAndError) {
  JobId id = Submit("job", 0);
  clock_.Advance(1000);
  ASSERT_TRUE(store_->SetJobState(id, JobState::kRunning).ok());
  int64_t started = *clock_.now;
  clock_.Advance(1000);
  ASSERT_TRUE(store_->SetJobState(id, JobState::kQueued).ok());  // requeue
  ASSERT_TRUE(store_->SetJobState(id, JobState::kRunning).ok());
  clock_.Advance(1000);
  ASSERT_TRUE(store_->SetJobState(id, JobState::kFailed, "agent crashed three times").ok());
  JobRecord job = **store_->GetJob(id);
  EXPECT_EQ(job.state, JobState::kFailed);
  EXPECT_EQ(job.started_at_ms, started);  // the first start
  EXPECT_EQ(job.finished_at_ms, *clock_.now);
  EXPECT_EQ(job.error, "agent crashed three times");
}

TEST_F(JobStoreTest, RejectsIllegalTransitions) {
  struct Case {
    std::vector<JobState> path;  // legal steps from queued
    JobState illegal;
  };
  using enum JobState;
  std::vector<Case> cases = {
      {{}, kDone},
      {{}, kFailed},
      {{}, kQueued},
      {{kPaused}, kRunning},
      {{kPaused}, kDone},
      {{kRunning, kDone}, kRunning},
      {{kRunning, kDone}, kQueued},
      {{kCancelled}, kQueued},
      {{kRunning, kDone}, kCancelled},
      {{}, kHeld},                    // only a running job is held
      {{kPaused}, kHeld},             // ... not one an operator paused
      {{kRunning, kHeld}, kRunning},  // a held job goes back through the queue
      {{kRunning, kHeld}, kDone},
  };
  for (const Case& c : cases) {
    JobId id = Submit("job", 0);
    for (JobState step : c.path) {
      std::optional<std::string> error;
      if (step == kFailed || step == kHeld) error = "x";
      ASSERT_TRUE(store_->SetJobState(id, step, error).ok());
    }
    JobState before = StateOf(id);
    std::optional<std::string> error;
    if (c.illegal == kFailed || c.illegal == kHeld) error = "x";
    Status status = store_->SetJobState(id, c.illegal, error);
    ASSERT_FALSE(status.ok()) << JobStateName(before) << " -> " << JobStateName(c.illegal);
    EXPECT_NE(status.error().find("illegal state transition " + std::string(JobStateName(before)) +
                                  " -> " + std::string(JobStateName(c.illegal))),
              std::string::npos)
        << status.error();
    EXPECT_EQ(StateOf(id), before);
  }
}

TEST_F(JobStoreTest, TransitionTableMatchesDiagram) {
  using enum JobState;
  const std::vector<JobState> all = {kQueued, kRunning, kPaused, kHeld, kDone, kFailed, kCancelled};
  int allowed = 0;
  for (JobState from : all) {
    for (JobState to : all) allowed += IsAllowedTransition(from, to) ? 1 : 0;
    if (IsTerminal(from)) {
      for (JobState to : all) EXPECT_FALSE(IsAllowedTransition(from, to));
    }
  }
  EXPECT_EQ(allowed, 14);  // the fourteen arrows of job_state.h
  for (JobState state : all) EXPECT_EQ(ParseJobState(JobStateName(state)), state);
}

TEST_F(JobStoreTest, ErrorTextRules) {
  JobId id = Submit("job", 0);
  ASSERT_TRUE(store_->SetJobState(id, JobState::kRunning).ok());
  EXPECT_FALSE(store_->SetJobState(id, JobState::kFailed).ok());        // needs a reason
  EXPECT_FALSE(store_->SetJobState(id, JobState::kHeld).ok());          // needs a reason
  EXPECT_FALSE(store_->SetJobState(id, JobState::kDone, "why").ok());   // takes none
  EXPECT_FALSE(store_->SetJobState(id + 50, JobState::kRunning).ok());  // no such job
  EXPECT_TRUE(store_->SetJobState(id, JobState::kCancelled, "operator").ok());
}

TEST_F(JobStoreTest, NextRunnableByPriorityThenSubmissionTime) {
  JobId low_old = Submit("low old", 0);
  clock_.Advance(10);
  JobId high_new = Submit("high new", 5);
  clock_.Advance(10);
  JobId low_new = Submit("low new", 0);
  JobId high_old_running = Submit("running", 9);
  ASSERT_TRUE(store_->SetJobState(high_old_running, JobState::kRunning).ok());
  clock_.Advance(10);
  JobId high_newest = Submit("high newest", 5);
  JobId paused = Submit("paused", 100);
  ASSERT_TRUE(store_->SetJobState(paused, JobState::kPaused).ok());

  Result<std::vector<JobRecord>> next = store_->NextRunnableJobs(10);
  ASSERT_TRUE(next.ok()) << next.error();
  std::vector<JobId> order;
  for (const JobRecord& job : *next) order.push_back(job.id);
  EXPECT_EQ(order, (std::vector<JobId>{high_new, high_newest, low_old, low_new}));
  EXPECT_EQ(store_->NextRunnableJobs(2)->size(), 2u);
}

TEST_F(JobStoreTest, ScenesAreIdempotentByHash) {
  std::vector<uint8_t> geometry(100000);
  for (size_t i = 0; i < geometry.size(); ++i) geometry[i] = static_cast<uint8_t>(i * 7);
  ASSERT_TRUE(store_->PutScene("big", geometry).ok());
  ASSERT_TRUE(store_->PutScene("big", geometry).ok());
  Status clash = store_->PutScene("big", std::vector<uint8_t>{1});
  ASSERT_FALSE(clash.ok());
  EXPECT_NE(clash.error().find("different bytes"), std::string::npos);
  EXPECT_EQ(**store_->GetScene("big"), geometry);
  EXPECT_FALSE(store_->GetScene("absent")->has_value());
  ASSERT_TRUE(store_->PutScene("empty", std::vector<uint8_t>{}).ok());
  EXPECT_TRUE(store_->GetScene("empty")->has_value());
}

TEST_F(JobStoreTest, DisplaysAreKeptPerJobAndReplaced) {
  const JobId id = Submit("drawn", 0);
  Result<std::optional<StoredDisplay>> none = store_->GetDisplay(id);
  ASSERT_TRUE(none.ok()) << none.error();
  EXPECT_FALSE(none->has_value());
  ASSERT_TRUE(store_->PutDisplay(id, 3, std::vector<uint8_t>{1, 2}).ok());
  ASSERT_TRUE(store_->PutDisplay(id, 4, std::vector<uint8_t>{3, 4, 5}).ok());
  Result<std::optional<StoredDisplay>> got = store_->GetDisplay(id);
  ASSERT_TRUE(got.ok() && got->has_value()) << got.error();
  EXPECT_EQ((*got)->round, 4u);
  EXPECT_EQ((*got)->display, (std::vector<uint8_t>{3, 4, 5}));
  // The display goes with its job.
  EXPECT_FALSE(store_->PutDisplay(id + 1, 0, std::vector<uint8_t>{1}).ok());
}

TEST_F(JobStoreTest, AgentsKeepFirstSeen) {
  ASSERT_TRUE(store_->RecordAgentSeen("a1", "10.0.0.1:7000", 8).ok());
  int64_t first = *clock_.now;
  clock_.Advance(5000);
  ASSERT_TRUE(store_->RecordAgentSeen("a1", "10.0.0.9:7000", 16).ok());
  std::vector<AgentRecord> agents = *store_->ListAgents();
  ASSERT_EQ(agents.size(), 1u);
  EXPECT_EQ(agents[0].address, "10.0.0.9:7000");
  EXPECT_EQ(agents[0].threads, 16u);
  EXPECT_EQ(agents[0].first_seen_ms, first);
  EXPECT_EQ(agents[0].last_seen_ms, *clock_.now);
}

TEST_F(JobStoreTest, EventsPerJobAndFarmWide) {
  JobId id = Submit("job", 0);
  for (int i = 0; i < 5; ++i) {
    ASSERT_TRUE(store_->AppendEvent(id, EventLevel::kInfo, "round " + std::to_string(i)).ok());
  }
  ASSERT_TRUE(store_->AppendEvent(std::nullopt, EventLevel::kWarning, "agent a1 lost").ok());
  // Text with quotes and SQL stays text: values are always bound.
  ASSERT_TRUE(store_->AppendEvent(id, EventLevel::kError, "'); DROP TABLE jobs; --").ok());
  std::vector<Event> last = *store_->ListEvents(id, 3);
  ASSERT_EQ(last.size(), 3u);
  EXPECT_EQ(last[0].text, "round 3");
  EXPECT_EQ(last[2].text, "'); DROP TABLE jobs; --");
  EXPECT_EQ(last[2].level, EventLevel::kError);
  std::vector<Event> farm = *store_->ListEvents(std::nullopt, 10);
  ASSERT_EQ(farm.size(), 1u);
  EXPECT_EQ(farm[0].level, EventLevel::kWarning);
  EXPECT_FALSE(farm[0].job.has_value());
  EXPECT_EQ(store_->ListJobs()->size(), 1u);
}

}  // namespace
}  // namespace radfarm::store
