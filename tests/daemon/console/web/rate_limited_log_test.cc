#include "daemon/console/web/rate_limited_log.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "loop/log.h"

namespace radfarm::web {
namespace {

using std::chrono::seconds;

TEST(RateLimitedLogTest, AtMostSoManyLinesPerWindowThenOneSummary) {
  std::vector<std::string> lines;
  loop::SetLogSink([&](std::string_view line) { lines.emplace_back(line); });
  RateLimitedLog log("http", "junk requests", 3, seconds(10));
  const RateLimitedLog::TimePoint t0{};
  for (int i = 0; i < 100; ++i) log.Warn("junk " + std::to_string(i), t0 + seconds(1));
  EXPECT_EQ(lines.size(), 3u);
  log.Flush(t0 + seconds(5));  // the window is not over
  EXPECT_EQ(lines.size(), 3u);
  log.Warn("later", t0 + seconds(12));
  loop::SetLogSink({});
  ASSERT_EQ(lines.size(), 5u);
  EXPECT_NE(lines[3].find("97 more junk requests were not logged (at most 3 lines per 10 s)"),
            std::string::npos)
      << lines[3];
  EXPECT_NE(lines[4].find("later"), std::string::npos);
}

}  // namespace
}  // namespace radfarm::web
