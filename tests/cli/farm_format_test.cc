// The farm commands' human-readable pieces: times, durations, rates, tables.
#include "cli/farm_format.h"

#include <gtest/gtest.h>

#include <cmath>

namespace radfarm {
namespace {

TEST(FarmFormatTest, UtcTimes) {
  EXPECT_EQ(FormatUtcTime(0), "1970-01-01 00:00:00 UTC");
  EXPECT_EQ(FormatUtcTime(1795000000123, /*with_ms=*/true), "2026-11-18 11:06:40.123 UTC");
  EXPECT_EQ(FormatUtcTime(-1, /*with_ms=*/true), "1969-12-31 23:59:59.999 UTC");
}

TEST(FarmFormatTest, DurationsRoundUpToTheSecond) {
  EXPECT_EQ(FormatDuration(0), "0s");
  EXPECT_EQ(FormatDuration(0.2), "1s");
  EXPECT_EQ(FormatDuration(59), "59s");
  EXPECT_EQ(FormatDuration(60), "1m00s");
  EXPECT_EQ(FormatDuration(185), "3m05s");
  EXPECT_EQ(FormatDuration(2 * 3600 + 7 * 60 + 3), "2h07m");
  EXPECT_EQ(FormatDuration(-1), "?");
  EXPECT_EQ(FormatDuration(NAN), "?");
  EXPECT_EQ(FormatDuration(INFINITY), "?");
}

TEST(FarmFormatTest, RaysPerSecondInMillions) {
  EXPECT_EQ(FormatRaysPerSecond(0), "0.00 Mrays/s");
  EXPECT_EQ(FormatRaysPerSecond(12345678), "12.35 Mrays/s");
}

TEST(FarmFormatTest, TableColumnsAlignWithoutTrailingSpaces) {
  EXPECT_EQ(FormatTable({{"ID", "NAME", "X"}, {"10", "a", ""}, {"2", "longer", "y"}}),
            "ID  NAME    X\n"
            "10  a\n"
            "2   longer  y\n");
}

TEST(FarmFormatTest, EventLinesAlignTheText) {
  EXPECT_EQ(FormatEvent({1795000000123, "info", "submitted"}),
            "2026-11-18 11:06:40.123 UTC  info     submitted");
  EXPECT_EQ(FormatEvent({1795000000123, "warning", "slow"}),
            "2026-11-18 11:06:40.123 UTC  warning  slow");
  // An event about a job names it (the farm's log holds every job's).
  EXPECT_EQ(FormatEvent({1795000000123, "info", "done: converged", 4}),
            "2026-11-18 11:06:40.123 UTC  info     job 4: done: converged");
}

}  // namespace
}  // namespace radfarm
