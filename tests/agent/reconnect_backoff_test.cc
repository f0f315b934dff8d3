#include "agent/reconnect_backoff.h"

#include <gtest/gtest.h>

#include <set>

namespace radfarm::agent {
namespace {

using std::chrono::milliseconds;

TEST(ReconnectBackoffTest, DelaysDoubleUpToTheCapWithinTheirJitterBounds) {
  for (uint64_t seed = 0; seed < 50; ++seed) {
    ReconnectBackoff backoff({milliseconds(100), milliseconds(10000)}, seed);
    int64_t base = 100;
    for (int attempt = 0; attempt < 20; ++attempt) {
      ASSERT_EQ(backoff.base().count(), base);
      const milliseconds delay = backoff.Next();
      EXPECT_GE(delay.count(), base / 2) << "seed " << seed << " attempt " << attempt;
      EXPECT_LE(delay.count(), base) << "seed " << seed << " attempt " << attempt;
      EXPECT_LE(delay.count(), 10000);
      base = std::min<int64_t>(base * 2, 10000);
    }
  }
}

TEST(ReconnectBackoffTest, JitterSpreadsTheDelays) {
  std::set<int64_t> first_delays;
  for (uint64_t seed = 0; seed < 50; ++seed) {
    ReconnectBackoff backoff({milliseconds(1000), milliseconds(10000)}, seed);
    first_delays.insert(backoff.Next().count());
  }
  // 50 draws from [500, 1000]: all equal would mean no jitter at all.
  EXPECT_GT(first_delays.size(), 10u);
}

TEST(ReconnectBackoffTest, ResetStartsOverAfterASuccess) {
  ReconnectBackoff backoff({milliseconds(100), milliseconds(10000)}, 1);
  for (int i = 0; i < 10; ++i) backoff.Next();
  EXPECT_EQ(backoff.base(), milliseconds(10000));
  backoff.Reset();
  EXPECT_EQ(backoff.base(), milliseconds(100));
  const milliseconds delay = backoff.Next();
  EXPECT_GE(delay, milliseconds(50));
  EXPECT_LE(delay, milliseconds(100));
}

TEST(ReconnectBackoffTest, TheSameSeedGivesTheSameDelays) {
  ReconnectBackoff a({milliseconds(100), milliseconds(10000)}, 42);
  ReconnectBackoff b({milliseconds(100), milliseconds(10000)}, 42);
  for (int i = 0; i < 10; ++i) EXPECT_EQ(a.Next(), b.Next());
}

}  // namespace
}  // namespace radfarm::agent
