#include "daemon/console/web/connection_deadlines.h"

#include <gtest/gtest.h>

namespace radfarm::web {
namespace {

using std::chrono::seconds;
using Clock = std::chrono::steady_clock;
using Key = ConnectionDeadlines::Key;

Key K(int i) { return reinterpret_cast<Key>(static_cast<uintptr_t>(i)); }

// A client trickling a byte every few seconds kept its connection for ever: libmicrohttpd's
// timeout restarts on every byte. The deadline runs from the connection's start, bytes or not.
TEST(ConnectionDeadlinesTest, AWaitingConnectionExpiresAtItsDeadline) {
  ConnectionDeadlines d(seconds(10), 64, 16);
  const Clock::time_point t0;
  EXPECT_TRUE(d.Opened(K(1), "10.0.0.1", 7, t0).empty());
  EXPECT_TRUE(d.Expired(t0 + seconds(9)).empty());
  EXPECT_EQ(d.Expired(t0 + seconds(10)), std::vector<int>{7});
  EXPECT_TRUE(d.Expired(t0 + seconds(11)).empty());  // returned once
}

TEST(ConnectionDeadlinesTest, AServingConnectionHasNoDeadlineUntilItsResponseIsDone) {
  ConnectionDeadlines d(seconds(10), 64, 16);
  const Clock::time_point t0;
  d.Opened(K(1), "10.0.0.1", 7, t0);
  d.Serving(K(1));
  EXPECT_TRUE(d.Expired(t0 + seconds(100)).empty());
  d.Waiting(K(1), t0 + seconds(100));
  EXPECT_TRUE(d.Expired(t0 + seconds(109)).empty());
  EXPECT_EQ(d.Expired(t0 + seconds(110)), std::vector<int>{7});
}

TEST(ConnectionDeadlinesTest, AClosedConnectionIsForgotten) {
  ConnectionDeadlines d(seconds(10), 64, 16);
  const Clock::time_point t0;
  d.Opened(K(1), "10.0.0.1", 7, t0);
  d.Closed(K(1));
  EXPECT_EQ(d.waiting(), 0u);
  EXPECT_TRUE(d.Expired(t0 + seconds(20)).empty());
}

// 16 slow connections from one address locked every other browser there out: now a new one
// closes that address's oldest waiting connection instead.
TEST(ConnectionDeadlinesTest, OverItsAddressCapANewConnectionClosesThatAddresssOldest) {
  ConnectionDeadlines d(seconds(10), 64, 2);
  const Clock::time_point t0;
  d.Opened(K(9), "10.0.0.9", 90, t0);
  d.Opened(K(1), "10.0.0.1", 10, t0);
  d.Opened(K(2), "10.0.0.1", 20, t0);
  d.Serving(K(2));                                          // serving: never closed for room
  EXPECT_TRUE(d.Opened(K(3), "10.0.0.1", 30, t0).empty());  // 1 and 3 waiting, 2 serving
  EXPECT_EQ(d.Opened(K(4), "10.0.0.1", 40, t0), std::vector<int>{10});
  EXPECT_EQ(d.Opened(K(5), "10.0.0.1", 50, t0), std::vector<int>{30});
  EXPECT_TRUE(d.Opened(K(6), "10.0.0.6", 60, t0).empty());
}

TEST(ConnectionDeadlinesTest, OverTheTotalCapANewConnectionClosesTheOldestWaiting) {
  ConnectionDeadlines d(seconds(10), 2, 16);
  const Clock::time_point t0;
  d.Opened(K(1), "10.0.0.1", 10, t0);
  d.Opened(K(2), "10.0.0.2", 20, t0);
  EXPECT_EQ(d.Opened(K(3), "10.0.0.3", 30, t0), std::vector<int>{10});
  EXPECT_EQ(d.waiting(), 2u);
}

}  // namespace
}  // namespace radfarm::web
