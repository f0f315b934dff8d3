#include "core/sobol.h"

#include <gtest/gtest.h>

#include <set>

namespace radfarm {
namespace {

// Every power-of-two prefix of a scrambled Sobol sequence is a (0, m, 2)-net in the first two
// dimensions (one point in each of the 2^m elementary intervals of any shape), and stratified in
// every single dimension.
TEST(SobolTest, PrefixesAreStratified) {
  const ScrambledSobol4 sobol(12345);
  const int m = 8;
  const uint32_t n = 1u << m;
  for (int kx = 0; kx <= m; ++kx) {
    std::set<std::pair<uint32_t, uint32_t>> cells;
    for (uint32_t i = 0; i < n; ++i) {
      const auto p = sobol.Point(i);
      cells.insert({uint32_t(p[0] * (1u << kx)), uint32_t(p[1] * (1u << (m - kx)))});
    }
    EXPECT_EQ(cells.size(), n) << "split " << kx;
  }
  for (int d = 0; d < ScrambledSobol4::kDimensions; ++d) {
    std::set<uint32_t> strata;
    for (uint32_t i = 0; i < n; ++i) strata.insert(uint32_t(sobol.Point(i)[d] * n));
    EXPECT_EQ(strata.size(), n) << "dimension " << d;
  }
}

TEST(SobolTest, SameSeedSamePointsOtherSeedOtherPoints) {
  const ScrambledSobol4 a(1), b(1), c(2);
  for (uint32_t i = 0; i < 100; ++i) {
    EXPECT_EQ(a.Point(i), b.Point(i));
    EXPECT_NE(a.Point(i), c.Point(i));
  }
}

TEST(SobolTest, PointsLieInTheUnitCube) {
  const ScrambledSobol4 s(99);
  for (uint32_t i = 0; i < 10000; i += 7) {
    for (double x : s.Point(i)) {
      EXPECT_GE(x, 0.0);
      EXPECT_LT(x, 1.0);
    }
  }
}

}  // namespace
}  // namespace radfarm
