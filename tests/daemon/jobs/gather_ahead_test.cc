// GatherAhead: the final gather's first batches planned before the shooting rounds end, leased
// through a scheduler of their own, and handed to the gather round when it starts.
#include "daemon/jobs/gather_ahead.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "tests/core/test_scenes.h"

namespace radfarm::daemon {
namespace {

using scheduler::BatchId;
using scheduler::MakeBatchId;

const scheduler::TimePoint kAheadStart{};

BatchResult AheadResultFor(uint32_t k) { return {{{k, 1}}, 0, 0, 0, 0}; }

// The gather round as RunningJob plans it: PlanPendingGather cut with the same sizing.
RoundPlan PlannedGatherRound(const ProgressiveSolver& solver, BatchSizing sizing, uint32_t round) {
  RoundPlan plan = solver.PlanPendingGather(sizing.batch_rays);
  TaperBatches(sizing.taper_ways, TaperFloor(sizing.batch_rays), &plan.batches);
  plan.round = round;
  return plan;
}

TEST(GatherAheadTest, PlansTheGatherRoundsFirstBatchesUpToTheRayLimit) {
  const PatchScene scene = testing::LitBox();
  const ProgressiveSolver solver(scene, testing::Gathering(64, 1 << 16));
  const BatchSizing sizing{40, 6};
  const RoundPlan round = PlannedGatherRound(solver, sizing, 3);
  ASSERT_GT(round.batches.size(), 10u);
  const std::optional<RoundPlan> ahead = GatherAhead::Plan(solver, sizing, 1000);
  ASSERT_TRUE(ahead);
  EXPECT_EQ(ahead->round, kGatherRound);
  EXPECT_LE(ahead->rays, 1000u);
  ASSERT_LT(ahead->batches.size(), round.batches.size());
  uint64_t rays = 0;
  for (size_t k = 0; k < ahead->batches.size(); ++k) {
    EXPECT_EQ(ahead->batches[k].round, kGatherRound);
    EXPECT_EQ(ahead->batches[k].shooter, round.batches[k].shooter);
    EXPECT_EQ(ahead->batches[k].first_ray, round.batches[k].first_ray);
    EXPECT_EQ(ahead->batches[k].ray_count, round.batches[k].ray_count);
    rays += ahead->batches[k].ray_count;
  }
  EXPECT_EQ(rays, ahead->rays);
  EXPECT_GT(rays + round.batches[ahead->batches.size()].ray_count, 1000u) << "as many as fit";
  // The whole gather when it fits; nothing when not one batch does, or no gather is pending.
  EXPECT_EQ(GatherAhead::Plan(solver, sizing, 1u << 30)->batches.size(), round.batches.size());
  EXPECT_FALSE(GatherAhead::Plan(solver, sizing, 10));
  const ProgressiveSolver shooting(scene, testing::Gathering(0, 1 << 16));
  EXPECT_FALSE(GatherAhead::Plan(shooting, sizing, 1u << 30));
}

// Results computed ahead go to the round with the agents that computed them; those of batches
// the round restored, or planned differently, do not; leases still out are named, and from then
// on it is only their results that come here.
TEST(GatherAheadTest, TheGatherRoundAdoptsTheResultsOfItsOwnBatches) {
  const PatchScene scene = testing::LitBox();
  const ProgressiveSolver solver(scene, testing::Gathering(64, 1 << 16));
  const BatchSizing sizing{40, 0};
  std::optional<RoundPlan> plan = GatherAhead::Plan(solver, sizing, 400);
  ASSERT_TRUE(plan);
  ASSERT_GE(plan->batches.size(), 8u);
  scheduler::SchedulerOptions options;
  options.initial_leases = 4;
  const std::vector<uint64_t> agents = {1, 2};
  Result<std::unique_ptr<GatherAhead>> made =
      GatherAhead::Start(*plan, sizing, options, kAheadStart, agents);
  ASSERT_TRUE(made.ok()) << made.error();
  GatherAhead& ahead = **made;
  EXPECT_TRUE(GatherAhead::Names(MakeBatchId(kGatherRound, 3)));
  EXPECT_FALSE(GatherAhead::Names(MakeBatchId(7, 3)));

  // Agent 1 computes batches 0-3; agent 2 holds 4-7 and answers none.
  for (uint64_t agent : agents) {
    for (int k = 0; k < 4; ++k) {
      const auto a = ahead.scheduler().NextAssignment(agent, kAheadStart);
      ASSERT_TRUE(a);
      if (agent == 2) continue;
      const uint32_t index = scheduler::BatchIndex(a->batch_id);
      ASSERT_EQ(ahead.scheduler()
                    .OnResult(agent, a->batch_id, a->attempt_id, AheadResultFor(index), kAheadStart)
                    .disposition,
                scheduler::Disposition::kAccepted);
      ahead.NoteAccepted(a->batch_id, "a1");
    }
  }
  EXPECT_EQ(ahead.accepted(), 4u);

  const RoundPlan round = PlannedGatherRound(solver, sizing, 7);
  const std::vector<uint32_t> restored = {2};
  GatherAhead::Adopted adopted = ahead.Adopt(round, restored);
  EXPECT_TRUE(ahead.adopted());
  ASSERT_EQ(adopted.results.size(), 3u);
  const std::vector<uint32_t> want = {0, 1, 3};
  for (size_t k = 0; k < want.size(); ++k) {
    EXPECT_EQ(adopted.results[k].first, want[k]);
    EXPECT_EQ(adopted.results[k].second, AheadResultFor(want[k]));
    EXPECT_EQ(adopted.agents[k], std::make_pair(want[k], std::string("a1")));
  }
  EXPECT_EQ(adopted.in_flight, (std::vector<uint32_t>{4, 5, 6, 7}));
  EXPECT_EQ(ahead.accepted(), 0u);
  // Batches never leased ahead are the round's to lease as it plans; those of leases still out
  // come back here when the leases end without a result, for the round to lease first.
  EXPECT_TRUE(ahead.TakeReturned().empty());
  ASSERT_EQ(ahead.scheduler().ReturnLeases(2, std::vector<BatchId>{MakeBatchId(kGatherRound, 5)}),
            1u);
  EXPECT_EQ(ahead.TakeReturned(), (std::vector<uint32_t>{5}));
  ahead.scheduler().OnAgentLost(2);
  std::vector<uint32_t> lost = ahead.TakeReturned();
  std::sort(lost.begin(), lost.end());
  EXPECT_EQ(lost, (std::vector<uint32_t>{4, 6, 7}));
  EXPECT_TRUE(ahead.TakeReturned().empty());

  // Planned with another batch size, the round has other batches: nothing is adopted.
  Result<std::unique_ptr<GatherAhead>> other =
      GatherAhead::Start(*plan, sizing, options, kAheadStart, agents);
  ASSERT_TRUE(other.ok());
  const auto a = (*other)->scheduler().NextAssignment(1, kAheadStart);
  ASSERT_TRUE(a);
  ASSERT_EQ((*other)
                ->scheduler()
                .OnResult(1, a->batch_id, a->attempt_id, AheadResultFor(0), kAheadStart)
                .disposition,
            scheduler::Disposition::kAccepted);
  (*other)->NoteAccepted(a->batch_id, "a1");
  EXPECT_TRUE((*other)->Adopt(PlannedGatherRound(solver, {30, 0}, 7), {}).results.empty());
}

}  // namespace
}  // namespace radfarm::daemon
