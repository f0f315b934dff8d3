#include "daemon/agents/door_keeper.h"

#include <gtest/gtest.h>

namespace radfarm::daemon {
namespace {

TEST(DoorKeeperTest, OverTheQuotaTheOldestStrangerGoesNotTheNewcomer) {
  DoorKeeper doors(2);
  EXPECT_EQ(doors.Admit(1), std::nullopt);
  EXPECT_EQ(doors.Admit(2), std::nullopt);
  EXPECT_EQ(doors.Admit(3), std::optional<uint64_t>(1));
  EXPECT_EQ(doors.Admit(4), std::optional<uint64_t>(2));
  EXPECT_EQ(doors.counters().unauthenticated, 2u);
  EXPECT_EQ(doors.counters().unauthenticated_peak, 2u);
  EXPECT_EQ(doors.counters().evicted, 2u);
  // An evicted connection's close was counted when it was evicted.
  EXPECT_FALSE(doors.ClosedBeforeAuth(1));
  EXPECT_EQ(doors.counters().closed_before_auth, 0u);
}

TEST(DoorKeeperTest, AnAuthenticatedAgentLeavesTheQuotaAndIsNeverEvicted) {
  DoorKeeper doors(1);
  EXPECT_EQ(doors.Admit(1), std::nullopt);
  doors.Authenticated(1);
  EXPECT_EQ(doors.counters().unauthenticated, 0u);
  EXPECT_EQ(doors.Admit(2), std::nullopt);  // 1 no longer counts
  EXPECT_EQ(doors.Admit(3), std::optional<uint64_t>(2));
  EXPECT_TRUE(doors.ClosedBeforeAuth(3));
  EXPECT_EQ(doors.counters().closed_before_auth, 1u);
  EXPECT_EQ(doors.counters().authenticated, 1u);
  EXPECT_EQ(doors.counters().accepted, 3u);
}

}  // namespace
}  // namespace radfarm::daemon
