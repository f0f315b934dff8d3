// JobRounds in-process (tests/daemon/master_parts.h): rounds advance as an agent's results arrive,
// a budgeted job ends done, max_running_jobs holds the rest in the queue, and pause and resume
// take a running job off its agents and back.
#include "daemon/jobs/job_rounds.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <optional>

#include "tests/daemon/agents/fake_agent.h"
#include "tests/daemon/master_parts.h"

namespace radfarm::daemon::fakes {
namespace {

uint32_t RoundsOf(MasterParts& master, uint64_t job) {
  RunningJob* runner = master.jobs().FindRunner(job);
  return runner ? runner->totals().round : 0;
}

TEST(JobRoundsTest, RoundsAdvanceAsAnAgentsResultsArrive) {
  MasterParts master;
  const uint64_t job = master.Submit(0);
  FakeAgent agent(master.loop(), master.agent_address(), master.secret(), "box-1", true);
  ASSERT_TRUE(agent.Connect().ok());
  ASSERT_TRUE(master.RunUntil([&] { return RoundsOf(master, job) >= 3; }));
  const RunningJob& runner = *master.jobs().FindRunner(job);
  EXPECT_GT(runner.totals().rays, 0u);
  EXPECT_LT(runner.totals().unshot_fraction, 1.0);
  EXPECT_GE(agent.results_sent(), agent.leased().size());
  EXPECT_EQ(master.StateOf(job), "running");
}

TEST(JobRoundsTest, AJobWithARayBudgetEndsDoneAndLeavesNoRunner) {
  MasterParts master;
  const uint64_t job = master.Submit(200000);
  FakeAgent agent(master.loop(), master.agent_address(), master.secret(), "box-1", true);
  ASSERT_TRUE(agent.Connect().ok());
  // Results were taken, and the job has no phase left (neither starting, nor running rounds, nor
  // drawing its display): it ended.
  ASSERT_TRUE(master.RunUntil(
      [&] { return agent.results_sent() > 0 && master.jobs().PhaseOf(job).empty(); }));
  EXPECT_EQ(master.StateOf(job), "done");
  EXPECT_GT(agent.results_sent(), 0u);
  EXPECT_TRUE(master.jobs().runners().empty());
}

TEST(JobRoundsTest, NoMoreJobsRunThanMaxRunningJobs) {
  MasterConfig config = TestMasterConfig();
  config.max_running_jobs = 1;
  MasterParts master(config);
  const uint64_t first = master.Submit(0);
  const uint64_t second = master.Submit(0);
  ASSERT_TRUE(master.RunUntil(
      [&] { return master.jobs().FindRunner(first) != nullptr && master.jobs().starting() == 0; }));
  EXPECT_EQ(master.jobs().runners().size(), 1u);
  EXPECT_EQ(master.StateOf(second), "queued");

  // The slot the first job leaves goes to the second.
  ASSERT_TRUE(master.Request(ControlCommand::kCancel, first).body["ok"].get<bool>());
  ASSERT_TRUE(master.RunUntil([&] { return master.jobs().FindRunner(second) != nullptr; }));
  EXPECT_EQ(master.jobs().FindRunner(first), nullptr);
  EXPECT_EQ(master.StateOf(first), "cancelled");
  EXPECT_EQ(master.StateOf(second), "running");
}

TEST(JobRoundsTest, APausedJobLeavesItsAgentsAndAResumedOneRunsAgain) {
  MasterParts master;
  const uint64_t job = master.Submit(0);
  FakeAgent agent(master.loop(), master.agent_address(), master.secret(), "box-1", false);
  ASSERT_TRUE(agent.Connect().ok());
  ASSERT_TRUE(master.RunUntil([&] { return !agent.held().empty(); }));

  ASSERT_TRUE(master.Request(ControlCommand::kPause, job).body["ok"].get<bool>());
  EXPECT_EQ(master.jobs().FindRunner(job), nullptr);
  ASSERT_TRUE(master.RunUntil([&] {
    return std::count(agent.cancelled_jobs().begin(), agent.cancelled_jobs().end(), job) == 1;
  }));
  EXPECT_TRUE(agent.held().empty());
  EXPECT_EQ(master.StateOf(job), "paused");

  const uint64_t received = agent.batches_received();
  ASSERT_TRUE(master.Request(ControlCommand::kResume, job).body["ok"].get<bool>());
  ASSERT_TRUE(master.RunUntil([&] { return master.jobs().FindRunner(job) != nullptr; }));
  EXPECT_EQ(master.StateOf(job), "running");
  // Its batches go out again: the agent dropped them with the Cancel.
  ASSERT_TRUE(master.RunUntil([&] { return agent.batches_received() > received; }));
  EXPECT_FALSE(agent.held().empty());
}

// With a final gather the solve starts from the direct light and the display computes its own
// at its points: ray work for the agents.
constexpr uint32_t kGatherRays = 64;

// A finished job's display is traced by the agents of protocol version 6, in pieces.
TEST(JobRoundsTest, TheDisplaysPiecesGoToTheAgents) {
  MasterParts master;
  const uint64_t job = master.Submit(0, 0, kGatherRays);
  FakeAgent agent(master.loop(), master.agent_address(), master.secret(), "box-1", true);
  ASSERT_TRUE(agent.Connect().ok());
  ASSERT_TRUE(master.RunUntil([&] { return master.StateOf(job) == "done"; }));
  EXPECT_GT(agent.pieces_received(), 0u);
  EXPECT_FALSE(master.jobs().LeasingPoints());
}

// Status read the store's round records, whose last may commit after the display began: the job
// showed fewer rays and rounds while its display was drawn than its rounds had shown.
TEST(JobRoundsTest, WhileTheDisplayIsDrawnTheJobShowsItsFinishedSolvesRoundsAndRays) {
  MasterParts master;
  const uint64_t job = master.Submit(0, 0, kGatherRays);
  FakeAgent agent(master.loop(), master.agent_address(), master.secret(), "box-1", true);
  agent.set_answering_pieces(false);
  ASSERT_TRUE(agent.Connect().ok());
  uint32_t last_round = 0;
  uint64_t last_rays = 0;
  ASSERT_TRUE(master.RunUntil([&] {
    if (RunningJob* runner = master.jobs().FindRunner(job)) {
      last_round = runner->totals().round;
      last_rays = runner->totals().rays;
    }
    return agent.pieces_held() > 0;
  }));
  const std::optional<SolveShown> solve = master.jobs().DisplayedSolve(job);
  ASSERT_TRUE(solve.has_value());
  EXPECT_GE(solve->round, last_round);  // its last round may end between two looks
  EXPECT_GE(solve->rays, last_rays);
  EXPECT_GT(solve->rays, 0u);
  const ControlResponse status = master.Request(ControlCommand::kStatus, job);
  EXPECT_EQ(status.body["job"]["phase"], "display");
  EXPECT_GE(status.body["job"]["rays"].get<uint64_t>(), solve->rays);
  EXPECT_GE(status.body["job"]["round"].get<uint32_t>(), solve->round);
  EXPECT_FALSE(master.jobs().DisplayedSolve(job + 1).has_value());
}

// A job's direct-light start is traced by the agents of protocol version 7, in pieces of its
// patches, and the solver starts from what they sent (the fake agent's grey light on every patch).
TEST(JobRoundsTest, TheStartsPatchesGoToTheAgentsAndTheSolverStartsFromThem) {
  MasterParts master;
  FakeAgent agent(master.loop(), master.agent_address(), master.secret(), "box-1", false);
  ASSERT_TRUE(agent.Connect().ok());
  ASSERT_TRUE(master.RunUntil([&] { return agent.authenticated(); }));
  const uint64_t job = master.Submit(0, 0, kGatherRays);
  ASSERT_TRUE(master.RunUntil([&] { return master.jobs().FindRunner(job) != nullptr; }));
  EXPECT_GT(agent.start_pieces_received(), 0u);
  const std::vector<Rgb>& direct = master.jobs().FindRunner(job)->direct_light();
  ASSERT_FALSE(direct.empty());
  EXPECT_TRUE(std::all_of(direct.begin(), direct.end(), [](const Rgb& e) {
    return e == Rgb{0.25, 0.25, 0.25};
  }));
  EXPECT_FALSE(master.jobs().LeasingPoints());
}

// A job cancelled while the compute thread waits for its start: the wait ends, the agents drop
// its pieces, and the master goes on (the next job starts, its start traced by the agent).
TEST(JobRoundsTest, ACancelDuringTheStartEndsTheWaitAndTheAgentsPieces) {
  MasterParts master;
  FakeAgent agent(master.loop(), master.agent_address(), master.secret(), "box-1", true);
  agent.set_answering_starts(false);
  ASSERT_TRUE(agent.Connect().ok());
  ASSERT_TRUE(master.RunUntil([&] { return agent.authenticated(); }));
  const uint64_t job = master.Submit(0, 0, kGatherRays);
  ASSERT_TRUE(master.RunUntil([&] { return agent.start_pieces_held() > 0; }));
  EXPECT_EQ(master.jobs().PhaseOf(job), "preparing");
  EXPECT_TRUE(master.jobs().LeasingPoints());
  ASSERT_TRUE(master.Request(ControlCommand::kCancel, job).body["ok"].get<bool>());
  ASSERT_TRUE(master.RunUntil(
      [&] { return agent.start_pieces_held() == 0 && master.jobs().starting() == 0; }));
  EXPECT_EQ(master.StateOf(job), "cancelled");
  EXPECT_FALSE(master.jobs().LeasingPoints());
  agent.set_answering_starts(true);
  const uint64_t next = master.Submit(200000, 0, kGatherRays);
  ASSERT_TRUE(master.RunUntil([&] { return master.StateOf(next) == "done"; }));
}

// An agent lost while it holds a start's pieces: they go to another agent, and the job starts.
TEST(JobRoundsTest, ALostAgentsStartPiecesGoToAnother) {
  MasterParts master;
  auto silent = std::make_unique<FakeAgent>(master.loop(), master.agent_address(), master.secret(),
                                            "box-1", true);
  silent->set_answering_starts(false);
  ASSERT_TRUE(silent->Connect().ok());
  ASSERT_TRUE(master.RunUntil([&] { return silent->authenticated(); }));
  const uint64_t job = master.Submit(0, 0, kGatherRays);
  ASSERT_TRUE(master.RunUntil([&] { return silent->start_pieces_held() > 0; }));
  FakeAgent other(master.loop(), master.agent_address(), master.secret(), "box-2", true);
  ASSERT_TRUE(other.Connect().ok());
  ASSERT_TRUE(master.RunUntil([&] { return other.authenticated(); }));
  silent->Drop();
  ASSERT_TRUE(master.RunUntil([&] { return master.jobs().FindRunner(job) != nullptr; }));
  EXPECT_GT(other.start_pieces_received(), 0u);
}

TEST(JobRoundsTest, ACancelDuringTheDisplayDropsItsPiecesOnTheAgents) {
  MasterParts master;
  const uint64_t job = master.Submit(0, 0, kGatherRays);
  FakeAgent agent(master.loop(), master.agent_address(), master.secret(), "box-1", true);
  agent.set_answering_pieces(false);
  ASSERT_TRUE(agent.Connect().ok());
  ASSERT_TRUE(master.RunUntil([&] { return agent.pieces_held() > 0; }));
  EXPECT_EQ(master.jobs().PhaseOf(job), "display");
  EXPECT_TRUE(master.jobs().LeasingPoints());
  ASSERT_TRUE(master.Request(ControlCommand::kCancel, job).body["ok"].get<bool>());
  ASSERT_TRUE(master.RunUntil([&] {
    return std::count(agent.cancelled_jobs().begin(), agent.cancelled_jobs().end(), job) > 0 &&
           agent.pieces_held() == 0;
  }));
  EXPECT_FALSE(master.jobs().LeasingPoints());
  EXPECT_EQ(master.StateOf(job), "cancelled");
}

TEST(JobRoundsTest, ALostAgentsPiecesGoToAnother) {
  MasterParts master;
  const uint64_t job = master.Submit(0, 0, kGatherRays);
  auto silent = std::make_unique<FakeAgent>(master.loop(), master.agent_address(), master.secret(),
                                            "box-1", true);
  silent->set_answering_pieces(false);
  ASSERT_TRUE(silent->Connect().ok());
  ASSERT_TRUE(master.RunUntil([&] { return silent->pieces_held() > 0; }));
  FakeAgent other(master.loop(), master.agent_address(), master.secret(), "box-2", true);
  ASSERT_TRUE(other.Connect().ok());
  ASSERT_TRUE(master.RunUntil([&] { return other.authenticated(); }));
  silent->Drop();
  ASSERT_TRUE(master.RunUntil([&] { return master.StateOf(job) == "done"; }));
  EXPECT_GT(other.pieces_received(), 0u);
}

}  // namespace
}  // namespace radfarm::daemon::fakes
