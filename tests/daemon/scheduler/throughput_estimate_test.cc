// ThroughputEstimate: smoothed rays/s, lease capacity and deadlines, on a fake clock.
#include "daemon/scheduler/throughput_estimate.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "tests/daemon/scheduler/fake_clock.h"

namespace radfarm::scheduler {
namespace {

using std::chrono::milliseconds;
using std::chrono::seconds;

TEST(ThroughputEstimateTest, StartsUnmeasuredWithTheInitialLeases) {
  SchedulerOptions options;
  options.initial_leases = 3;
  ThroughputEstimate t;
  EXPECT_FALSE(t.measured());
  EXPECT_EQ(t.rays_per_second(), 0);
  EXPECT_EQ(t.LeaseCapacity(4096, options), 3u);
  EXPECT_EQ(t.Deadline(4096, kT0, options), kT0 + seconds(8));  // 4 x 2 s unmeasured
}

TEST(ThroughputEstimateTest, MeasuresBusyTimeBetweenResults) {
  ThroughputEstimate t;
  // Two leases issued together, answered 100 ms apart: 1000 rays per 100 ms each.
  t.AddResult(1000, kT0, kT0 + milliseconds(100), 0.5);
  t.AddResult(1000, kT0, kT0 + milliseconds(200), 0.5);
  EXPECT_NEAR(t.rays_per_second(), 10000, 1e-6);
  // After an idle second only the time since the lease was issued counts.
  t.AddResult(1000, kT0 + milliseconds(1200), kT0 + milliseconds(1300), 0.5);
  EXPECT_NEAR(t.rays_per_second(), 10000, 1e-6);
}

TEST(ThroughputEstimateTest, BurstOfResultsDoesNotBlowUpTheEstimate) {
  ThroughputEstimate t;
  // Eight threads finish eight 1000-ray leases at the same instant, 1 s after issue.
  for (int k = 0; k < 8; ++k) t.AddResult(1000, kT0, kT0 + seconds(1), 0.3);
  EXPECT_LT(t.rays_per_second(), 1e6);  // averaging the ratios would give ~1e6 (1 ms floor)
  EXPECT_GT(t.rays_per_second(), 1000);
}

// A round's last shots are a ray or two per shooter: measured at the 1 ms floor each, they
// would read an agent of 1e6 rays/s as 1e3. Once measured, results under min_rays only mark the
// time; an unmeasured agent adds its first results up until they reach min_rays.
TEST(ThroughputEstimateTest, TinyResultsDoNotShrinkTheEstimate) {
  ThroughputEstimate t;
  TimePoint now = kT0;
  for (int k = 0; k < 10; ++k) {
    const TimePoint issued = now;
    now += milliseconds(4);
    t.AddResult(4096, issued, now, 0.3, 256);  // 1.024e6 rays/s
  }
  ASSERT_NEAR(t.rays_per_second(), 1.024e6, 1);
  for (int k = 0; k < 1000; ++k) {
    const TimePoint issued = now;
    now += milliseconds(1);
    t.AddResult(2, issued, now, 0.3, 256);
  }
  EXPECT_NEAR(t.rays_per_second(), 1.024e6, 1);
  // The busy time of the next real result starts at the last tiny one, not at its issue.
  t.AddResult(4096, kT0, now + milliseconds(4), 0.3, 256);
  EXPECT_NEAR(t.rays_per_second(), 1.024e6, 1);
  // Without the threshold the same results drag it down to about 2000 rays/s.
  ThroughputEstimate plain;
  plain.AddResult(4096, kT0, kT0 + milliseconds(4), 0.3);
  for (int k = 0; k < 100; ++k) plain.AddResult(2, kT0, kT0 + milliseconds(5 + k), 0.3);
  EXPECT_LT(plain.rays_per_second(), 1e4);
  ThroughputEstimate first_tiny;
  first_tiny.AddResult(2, kT0, kT0 + milliseconds(1), 0.3, 256);
  EXPECT_FALSE(first_tiny.measured());
  first_tiny.AddResult(254, kT0, kT0 + milliseconds(2), 0.3, 256);
  ASSERT_TRUE(first_tiny.measured());
  EXPECT_NEAR(first_tiny.rays_per_second(), 256 / 2e-3, 1e-6);  // both results, both busy times
}

// A master restarted mid-job meets its agents in a round of 23-ray batches (one shooter's share
// of a 352,679-patch job). The first lease was answered 430 ms after it went out; read from two
// batches that made 106 rays/s, and every later lease (1 batch, then 6 held) stayed under
// min_rays, so the estimate never moved and the rest of the job ran at a round trip per 23 rays
// (restart_bench: 151.9 s against 54.9 s without the kill). Leases now always carry enough
// batches to be measured, and the first measurement needs min_rays too.
TEST(ThroughputEstimateTest, ASlowFirstLeaseOfTinyBatchesDoesNotPinTheEstimate) {
  SchedulerOptions options;  // target 0.5 s, min_batch_rays 256
  options.max_leases_per_agent = 1u << 17;
  const double batch_rays = 23;
  const double agent_rays_per_second = 1e6;
  const auto round_trip = milliseconds(20);
  ThroughputEstimate t;
  TimePoint now = kT0;
  EXPECT_EQ(t.LeaseBatches(batch_rays, options), 12u);  // ceil(256 / 23), not initial_leases (2)
  EXPECT_EQ(t.LeaseCapacity(batch_rays, options), 12u);
  for (int lease = 0; lease < 60; ++lease) {
    const uint64_t rays = uint64_t(t.LeaseBatches(batch_rays, options) * batch_rays);
    EXPECT_GE(rays, options.min_batch_rays);
    const TimePoint issued = now;
    const auto stall = lease == 0 ? milliseconds(430) : milliseconds(0);
    now += stall + round_trip +
           std::chrono::duration_cast<Duration>(
               std::chrono::duration<double>(double(rays) / agent_rays_per_second));
    t.AddResult(rays, issued, now, options.throughput_smoothing, options.min_batch_rays);
    ASSERT_TRUE(t.measured());
  }
  // Leases of 0.5 s at a million rays/s take 20 ms more each: within a few per cent of the speed.
  EXPECT_GT(t.rays_per_second(), 0.9 * agent_rays_per_second);
  EXPECT_GT(t.LeaseBatches(batch_rays, options), 18000u);
}

TEST(ThroughputEstimateTest, FastAgentsHoldMoreLeasesNeverAboveTheCap) {
  SchedulerOptions options;
  options.target_lease_seconds = 0.5;
  options.max_leases_per_agent = 16;
  ThroughputEstimate slow, fast, very_fast;
  slow.AddResult(1000, kT0, kT0 + seconds(1), 0.3);            // 1e3 rays/s
  fast.AddResult(100000, kT0, kT0 + seconds(1), 0.3);          // 1e5 rays/s
  very_fast.AddResult(100000000, kT0, kT0 + seconds(1), 0.3);  // 1e8 rays/s
  EXPECT_EQ(slow.LeaseCapacity(4096, options), 1u);            // never 0
  EXPECT_EQ(fast.LeaseCapacity(4096, options), 12u);           // 1e5 * 0.5 / 4096
  EXPECT_EQ(very_fast.LeaseCapacity(4096, options), 16u);
}

TEST(ThroughputEstimateTest, SpareLeasesComeOnTopOfTheTargetOnceMeasured) {
  SchedulerOptions options;
  options.target_lease_seconds = 0.5;
  options.initial_leases = 3;
  options.max_leases_per_agent = 16;
  options.spare_leases = 1;
  ThroughputEstimate unmeasured, slow, fast, very_fast;
  slow.AddResult(1000, kT0, kT0 + seconds(1), 0.3);            // 1e3 rays/s
  fast.AddResult(100000, kT0, kT0 + seconds(1), 0.3);          // 1e5 rays/s
  very_fast.AddResult(100000000, kT0, kT0 + seconds(1), 0.3);  // 1e8 rays/s
  EXPECT_EQ(unmeasured.LeaseCapacity(4096, options), 3u);      // initial_leases only
  EXPECT_EQ(slow.LeaseCapacity(4096, options), 2u);            // the one it runs + a spare
  EXPECT_EQ(fast.LeaseCapacity(4096, options), 13u);           // 12 + 1
  EXPECT_EQ(very_fast.LeaseCapacity(4096, options), 16u);      // the cap holds
}

TEST(ThroughputEstimateTest, AReportedSpeedSizesLeasesUntilTheFirstMeasurement) {
  SchedulerOptions options;
  options.target_lease_seconds = 0.5;
  options.initial_leases = 2;
  options.max_leases_per_agent = 64;
  options.spare_leases = 1;
  ThroughputEstimate t;
  t.SetReportedSpeed(1e5);  // its heartbeat: 1e5 rays/s on its recent batches
  EXPECT_FALSE(t.measured());
  EXPECT_EQ(t.rays_per_second(), 0);               // a report is no measurement
  EXPECT_EQ(t.LeaseBatches(4096, options), 12u);   // 1e5 * 0.5 / 4096
  EXPECT_EQ(t.LeaseCapacity(4096, options), 13u);  // + the spare
  // The first lease may wait on a scene fetch: expected times and deadlines stay unmeasured's.
  EXPECT_EQ(t.ExpectedSeconds(4096, options), options.unmeasured_expected_seconds);
  EXPECT_EQ(t.Deadline(4096, kT0, options), kT0 + seconds(8));
  // A slow report never gives fewer than the initial leases.
  t.SetReportedSpeed(10);
  EXPECT_EQ(t.LeaseBatches(4096, options), 2u);
  EXPECT_EQ(t.LeaseCapacity(4096, options), 2u);
  // Nonsense is no report.
  for (double bad : {-1.0, 0.0, std::nan(""), std::numeric_limits<double>::infinity()}) {
    t.SetReportedSpeed(bad);
    EXPECT_EQ(t.LeaseBatches(4096, options), 2u) << bad;
  }
  // The first measurement replaces the report: 1000 rays/s measured, 1e5 reported.
  t.SetReportedSpeed(1e5);
  t.AddResult(1000, kT0, kT0 + seconds(1), 0.3);
  EXPECT_TRUE(t.measured());
  EXPECT_EQ(t.LeaseBatches(4096, options), 1u);
  EXPECT_EQ(t.LeaseCapacity(4096, options), 2u);
}

TEST(ThroughputEstimateTest, DeadlineIsAMultipleOfTheHeldWorkWithAFloor) {
  SchedulerOptions options;
  options.deadline_multiple = 4;
  options.deadline_floor = seconds(2);
  ThroughputEstimate t;
  t.AddResult(1000, kT0, kT0 + seconds(1), 0.3);                 // 1000 rays/s
  EXPECT_EQ(t.Deadline(100, kT0, options), kT0 + seconds(2));    // 0.4 s: the floor
  EXPECT_EQ(t.Deadline(5000, kT0, options), kT0 + seconds(20));  // 4 x 5 s
}

}  // namespace
}  // namespace radfarm::scheduler
