#include "base/latency_histogram.h"

#include <gtest/gtest.h>

namespace radfarm {
namespace {

TEST(LatencyHistogramTest, BoundsAreInclusiveAndBeyondTheLastCountsOnlyInTheTotal) {
  LatencyHistogram h;
  h.Record(0.005);  // exactly a bound: in it
  h.Record(0.0051);
  h.Record(100);
  EXPECT_EQ(h.CountAtMost(0), 1u);
  EXPECT_EQ(h.CountAtMost(1), 2u);
  EXPECT_EQ(h.CountAtMost(LatencyHistogram::kBounds.size() - 1), 2u);
  EXPECT_EQ(h.count(), 3u);
  EXPECT_DOUBLE_EQ(h.sum(), 100.0101);
}

}  // namespace
}  // namespace radfarm
