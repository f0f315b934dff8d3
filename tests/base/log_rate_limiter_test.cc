#include "base/log_rate_limiter.h"

#include <gtest/gtest.h>

namespace radfarm {
namespace {

TEST(LogRateLimiterTest, AllowsLinesPerWindowAndSummarisesTheRestOnceItEnds) {
  using std::chrono::seconds;
  LogRateLimiter limiter(3, seconds(10));
  const LogRateLimiter::TimePoint t0{};
  for (int i = 0; i < 3; ++i) EXPECT_TRUE(limiter.Allow(t0 + seconds(1)));
  EXPECT_FALSE(limiter.Allow(t0 + seconds(2)));
  EXPECT_FALSE(limiter.Allow(t0 + seconds(9)));
  EXPECT_EQ(limiter.TakeSuppressed(t0 + seconds(5)), std::nullopt);  // window not over
  EXPECT_EQ(limiter.TakeSuppressed(t0 + seconds(11)), std::optional<uint64_t>(2));
  EXPECT_EQ(limiter.TakeSuppressed(t0 + seconds(30)), std::nullopt);  // said once
  EXPECT_TRUE(limiter.Allow(t0 + seconds(31)));
  EXPECT_EQ(limiter.suppressed_total(), 2u);
}

}  // namespace
}  // namespace radfarm
