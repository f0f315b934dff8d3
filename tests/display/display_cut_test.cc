// The display's cut threshold: slivers between gathered corners are cut at half the contrast.
#include "display/display_cut.h"

#include <gtest/gtest.h>

#include <cmath>

namespace radfarm {
namespace {

TEST(DisplayCutTest, QualityIsOneForAnEquilateralTriangleAndFallsAsItFlattens) {
  const Vec3 a{0, 0, 0}, b{1, 0, 0};
  EXPECT_NEAR(TriangleQuality(a, b, {0.5, std::sqrt(3.0) / 2, 0}), 1.0, 1e-12);
  // A right isosceles triangle: area 1/2, squared edges 1 + 1 + 2.
  EXPECT_NEAR(TriangleQuality(a, b, {0, 1, 0}), std::sqrt(3.0) / 2, 1e-12);
  // Halved twice along its long side by the cuts beside it: a sliver.
  EXPECT_LT(TriangleQuality(a, {1, 0, 0}, {0.25, 0.1, 0}), kSliverQuality);
  EXPECT_EQ(TriangleQuality(a, b, {2, 0, 0}), 0.0);  // flat
  EXPECT_EQ(TriangleQuality(a, a, a), 0.0);          // a point
  // Any orientation and scale.
  EXPECT_NEAR(TriangleQuality({5, 5, 5}, {5, 5, 105}, {5, 105, 5}), std::sqrt(3.0) / 2, 1e-12);
}

TEST(DisplayCutTest, OnlySliversOfGatheredCornersAreCutAtHalfTheContrast) {
  const Vec3 a{0, 0, 0}, b{0.12, 0, 0};
  const Vec3 round{0.06, 0.1, 0}, thin{0.01, 0.004, 0};
  EXPECT_EQ(CutContrast(a, b, round, true), kRefineContrast);
  EXPECT_EQ(CutContrast(a, b, thin, true), kSliverContrast);
  // The direct light's contrast (a shadow's edge) does not depend on the triangle's shape.
  EXPECT_EQ(CutContrast(a, b, thin, false), kRefineContrast);
  EXPECT_LT(kSliverContrast, kRefineContrast);
}

}  // namespace
}  // namespace radfarm
