#include "daemon/agents/job_blocklist.h"

#include <gtest/gtest.h>

namespace radfarm::daemon {
namespace {

using std::chrono::seconds;
const scheduler::TimePoint kT0{seconds(1000)};

TEST(JobBlocklistTest, ThreeStrikesBlocklistTheAgentForThatJobOnly) {
  JobBlocklist list(seconds(600));
  EXPECT_FALSE(list.Strike(1, "node-a", kT0).has_value());
  EXPECT_FALSE(list.Strike(1, "node-a", kT0 + seconds(1)).has_value());
  EXPECT_EQ(list.Strikes(1, "node-a", kT0 + seconds(1)), 2u);
  EXPECT_FALSE(list.BlockedUntil(1, "node-a", kT0 + seconds(1)));
  const auto until = list.Strike(1, "node-a", kT0 + seconds(2));
  ASSERT_TRUE(until);
  EXPECT_EQ(*until, kT0 + seconds(602));
  EXPECT_EQ(list.BlockedUntil(1, "node-a", kT0 + seconds(601)), until);
  // Another job, another agent (even on the same host): not affected.
  EXPECT_FALSE(list.BlockedUntil(2, "node-a", kT0 + seconds(3)));
  EXPECT_FALSE(list.BlockedUntil(1, "node-b", kT0 + seconds(3)));
}

TEST(JobBlocklistTest, ABlocklistingExpires) {
  JobBlocklist list(seconds(60));
  for (int k = 0; k < 3; ++k) (void)list.Strike(1, "a", kT0);
  EXPECT_TRUE(list.BlockedUntil(1, "a", kT0 + seconds(59)));
  EXPECT_FALSE(list.BlockedUntil(1, "a", kT0 + seconds(60)));
  // It starts counting afresh.
  EXPECT_EQ(list.Strikes(1, "a", kT0 + seconds(60)), 0u);
  EXPECT_FALSE(list.Strike(1, "a", kT0 + seconds(60)).has_value());
}

TEST(JobBlocklistTest, StrikesFurtherApartThanTheDurationDoNotAddUp) {
  JobBlocklist list(seconds(60));
  EXPECT_FALSE(list.Strike(1, "a", kT0).has_value());
  EXPECT_FALSE(list.Strike(1, "a", kT0 + seconds(50)).has_value());
  EXPECT_FALSE(list.Strike(1, "a", kT0 + seconds(100)).has_value());  // the first has expired
  EXPECT_EQ(list.Strikes(1, "a", kT0 + seconds(100)), 2u);
  EXPECT_TRUE(list.Strike(1, "a", kT0 + seconds(101)));
}

TEST(JobBlocklistTest, ExpiredEntriesAreForgotten) {
  JobBlocklist list(seconds(60));
  for (int job = 0; job < 100; ++job) (void)list.Strike(job, "a", kT0);
  EXPECT_EQ(list.size(), 100u);
  (void)list.Strike(1000, "b", kT0 + seconds(61));
  EXPECT_EQ(list.size(), 1u);
}

}  // namespace
}  // namespace radfarm::daemon
