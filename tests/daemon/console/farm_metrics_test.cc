#include "daemon/console/farm_metrics.h"

#include <gtest/gtest.h>

namespace radfarm::daemon {
namespace {

using nlohmann::json;

TEST(FarmMetricsTest, JobsAndAgentsAreCountedByStateWithEveryStateListed) {
  const json jobs = json::array({{{"state", "running"}, {"rays", 100}, {"rays_per_second", 2.5}},
                                 {{"state", "running"}, {"rays", 50}, {"rays_per_second", 1.5}},
                                 {{"state", "done"}, {"rays", 1000}, {"rays_per_second", 0.0}}});
  const json agents = json::array({{{"stale", false}, {"leases", 2}},
                                   {{"stale", false}, {"leases", 0}},
                                   {{"stale", true}, {"leases", 1}}});
  const web::FarmMetrics m = FarmMetricsOf(jobs, agents, {}, {}, 7);
  EXPECT_EQ(m.jobs_by_state.at("running"), 2u);
  EXPECT_EQ(m.jobs_by_state.at("done"), 1u);
  EXPECT_EQ(m.jobs_by_state.at("queued"), 0u);
  EXPECT_EQ(m.jobs_by_state.at("cancelled"), 0u);
  EXPECT_EQ(m.jobs_by_state.at("held"), 0u);
  EXPECT_EQ(m.jobs_by_state.size(), 7u);
  EXPECT_EQ(m.agents_by_state.at("busy"), 1u);
  EXPECT_EQ(m.agents_by_state.at("idle"), 1u);
  EXPECT_EQ(m.agents_by_state.at("stale"), 1u);
  EXPECT_DOUBLE_EQ(m.rays_per_second, 4.0);
  EXPECT_EQ(m.rays_total, 1150u);
  EXPECT_EQ(m.store_queue_depth, 7u);
}

TEST(FarmMetricsTest, DroppedResultsAreSplitIntoRejectionsAndLateOnes) {
  scheduler::SchedulerCounters a;
  a.attempts_issued = 10;
  a.speculative_attempts = 1;
  a.leases_requeued = 2;
  a.leases_preempted = 5;
  a.results_accepted = 8;
  a.results_dropped[size_t(scheduler::DropReason::kInvalid)] = 1;
  a.results_dropped[size_t(scheduler::DropReason::kNotHolder)] = 2;
  a.results_dropped[size_t(scheduler::DropReason::kLate)] = 3;
  BatchTotals totals;
  totals.Add(a);
  totals.Add(a);
  const web::FarmMetrics m = FarmMetricsOf(json::array(), json::array(), totals, {}, 0);
  EXPECT_EQ(m.batches_issued, 20u);
  EXPECT_EQ(m.batches_reissued_overdue, 2u);
  EXPECT_EQ(m.batches_reissued_requeued, 4u);
  EXPECT_EQ(m.leases_preempted, 10u);
  EXPECT_EQ(m.results_accepted, 16u);
  EXPECT_EQ(m.results_rejected.at("invalid"), 2u);
  EXPECT_EQ(m.results_rejected.at("not_the_holder"), 4u);
  EXPECT_EQ(m.results_rejected.count("late"), 0u);
  EXPECT_EQ(m.results_dropped.at("late"), 6u);
  EXPECT_EQ(m.results_dropped.at("stale_round"), 0u);
}

TEST(FarmMetricsTest, VerifiedAndMismatchedBatchesAreCounted) {
  BatchTotals totals;
  totals.verified = 40;
  totals.verify_mismatches = 1;
  const web::FarmMetrics m = FarmMetricsOf(json::array(), json::array(), totals, {}, 0);
  EXPECT_EQ(m.batches_verified, 40u);
  EXPECT_EQ(m.verify_mismatches, 1u);
}

}  // namespace
}  // namespace radfarm::daemon
