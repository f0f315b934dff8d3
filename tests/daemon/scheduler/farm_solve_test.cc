// Whole solves driven through the scheduler by simulated agents give radiosity bit-identical to
// Solve() (the round driver on a thread pool) with the same settings, whatever the agents do
// (core/batch.h's contract).
#include <gtest/gtest.h>

#include <cstring>

#include "solve/local_solve.h"
#include "tests/core/test_scenes.h"
#include "tests/daemon/scheduler/farm_sim.h"

namespace radfarm::scheduler {
namespace {

using std::chrono::milliseconds;
using std::chrono::seconds;
using testing::FarmSim;
using testing::SimAgentSpec;

using radfarm::testing::LitBox;

SolverSettings Settings() {
  SolverSettings s;
  s.shot_rays = 1 << 14;
  s.tolerance = 0.02;
  s.threads = 2;
  return s;
}

class FarmSolveTest : public ::testing::Test {
 protected:
  // Solves through the farm with batches of 1000 rays (core's Solve uses 4096) and compares.
  void ExpectSameAsSolve(FarmSim& farm) {
    const std::vector<Rgb> farmed = farm.Solve(1000);
    ASSERT_EQ(farmed.size(), reference_.radiosity.size());
    EXPECT_EQ(std::memcmp(farmed.data(), reference_.radiosity.data(), farmed.size() * sizeof(Rgb)),
              0);
    EXPECT_EQ(farm.rounds(), reference_.stats.rounds);
  }

  const PatchScene scene_ = LitBox();
  const SolveResult reference_ = radfarm::Solve(scene_, Settings());
};

TEST_F(FarmSolveTest, OneAgent) {
  FarmSim farm(scene_, Settings(), {SimAgentSpec{}});
  ExpectSameAsSolve(farm);
  const SchedulerCounters c = farm.scheduler().counters(farm.now());
  EXPECT_EQ(c.attempts_issued, c.results_accepted);
  EXPECT_EQ(c.speculative_attempts, 0u);
}

TEST_F(FarmSolveTest, FiveAgentsOfDifferentSpeeds) {
  std::vector<SimAgentSpec> agents(5);
  double speed = 1e4;  // rays/s: 1e4, 3e4, ... 8.1e5
  for (SimAgentSpec& agent : agents) {
    agent.rays_per_second = speed;
    speed *= 3;
  }
  FarmSim farm(scene_, Settings(), agents);
  ExpectSameAsSolve(farm);
  const SchedulerCounters c = farm.scheduler().counters(farm.now());
  ASSERT_EQ(c.agents.size(), 5u);
  // The four faster ones all contribute; the slowest (81 times slower than the fastest) may lose
  // every batch it held to takeovers and copies at the rounds' ends, which is the point of them.
  for (size_t k = 1; k < c.agents.size(); ++k) {
    EXPECT_GT(c.agents[k].results_accepted, 0u) << c.agents[k].agent;
  }
  EXPECT_GT(c.agents[4].results_accepted, c.agents[0].results_accepted);
}

TEST_F(FarmSolveTest, AgentsThatDieMidRoundHaveTheirLeasesRequeued) {
  std::vector<SimAgentSpec> agents(4);
  agents[0].dies_at = milliseconds(15);
  agents[1].dies_at = milliseconds(75);
  FarmSim farm(scene_, Settings(), agents);
  ExpectSameAsSolve(farm);
  const SchedulerCounters c = farm.scheduler().counters(farm.now());
  EXPECT_GT(c.leases_requeued, 0u);
  EXPECT_EQ(c.agents.size(), 2u);  // the dead are forgotten
}

TEST_F(FarmSolveTest, DuplicatedAndLateResultsAreDropped) {
  std::vector<SimAgentSpec> agents(3);
  agents[0].sends_twice = true;
  agents[1].result_delay = seconds(20);  // far past its first leases' deadline
  FarmSim farm(scene_, Settings(), agents);
  ExpectSameAsSolve(farm);
  farm.Drain(seconds(30));
  const SchedulerCounters c = farm.scheduler().counters(farm.now());
  EXPECT_GT(c.dropped(DropReason::kDuplicate), 0u);
  EXPECT_GT(c.speculative_attempts + c.takeovers, 0u);  // its leases went to others
  EXPECT_GT(c.dropped(DropReason::kLate) + c.dropped(DropReason::kStaleRound), 0u);
}

TEST_F(FarmSolveTest, StragglersAreReissuedAndBothAttemptsAnswer) {
  std::vector<SimAgentSpec> agents(3);
  agents[2].stalls_at = milliseconds(20);
  FarmSim farm(scene_, Settings(), agents);
  ExpectSameAsSolve(farm);
  farm.Drain(seconds(600));  // the straggler finishes what it held
  const SchedulerCounters c = farm.scheduler().counters(farm.now());
  EXPECT_GT(c.speculative_attempts + c.takeovers, 0u);
  EXPECT_GT(c.dropped(DropReason::kLate) + c.dropped(DropReason::kStaleRound), 0u);
}

TEST_F(FarmSolveTest, AnAgentReturningLeases) {
  std::vector<SimAgentSpec> agents(2);
  agents[0].returns_leases_at = milliseconds(30);
  FarmSim farm(scene_, Settings(), agents);
  ExpectSameAsSolve(farm);
  EXPECT_GT(farm.scheduler().counters(farm.now()).leases_requeued, 0u);
}

TEST_F(FarmSolveTest, ALyingAgentIsRejectedBlocklistedAndItsWorkRedone) {
  std::vector<SimAgentSpec> agents(3);
  agents[1].lies_on_result = 2;
  FarmSim farm(scene_, Settings(), agents);
  ExpectSameAsSolve(farm);
  const SchedulerCounters c = farm.scheduler().counters(farm.now());
  EXPECT_EQ(c.dropped(DropReason::kInvalid), 1u);
  ASSERT_EQ(c.agents.size(), 3u);
  EXPECT_TRUE(c.agents[1].blocklisted);
  EXPECT_EQ(c.agents[1].leases_held, 0u);
  EXPECT_EQ(c.agents[1].results_accepted, 2u);  // nothing after the lie
}

// The final gather's round is ordinary batches: agents that die mid-gather have those requeued,
// and the gathered radiosity is Solve()'s to the bit.
TEST(FarmGatherTest, AGatheredSolveWithAgentsDyingIsBitIdenticalToSolve) {
  const PatchScene scene = LitBox();
  SolverSettings settings = Settings();
  settings.gather_rays = 256;
  const SolveResult reference = radfarm::Solve(scene, settings);
  ASSERT_EQ(reference.unshot, std::vector<Rgb>(scene.patches.size())) << "gathered";
  // The gather round is the last and longest: an agent dying at 90% of a clean run's simulated
  // time dies in it.
  std::vector<SimAgentSpec> agents(3);
  for (SimAgentSpec& agent : agents) agent.rays_per_second = 2e4;  // rounds of many 10 ms steps
  FarmSim clean(scene, settings, agents);
  const auto start = clean.now();
  clean.Solve(1000);
  agents[0].dies_at = std::chrono::duration_cast<milliseconds>((clean.now() - start) * 0.9);
  FarmSim farm(scene, settings, agents);
  const std::vector<Rgb> farmed = farm.Solve(1000);
  ASSERT_EQ(farmed.size(), reference.radiosity.size());
  EXPECT_EQ(std::memcmp(farmed.data(), reference.radiosity.data(), farmed.size() * sizeof(Rgb)), 0);
  EXPECT_EQ(farm.rounds(), reference.stats.rounds);
  EXPECT_GT(farm.scheduler().counters(farm.now()).leases_requeued, 0u);
}

}  // namespace
}  // namespace radfarm::scheduler
