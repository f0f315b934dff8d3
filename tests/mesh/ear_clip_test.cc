#include "mesh/ear_clip.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace radfarm {
namespace {

double TriangulatedArea(const std::vector<Point2>& p, const EarClipResult& r) {
  double sum = 0;
  for (const auto& t : r.triangles) {
    const double a = Orient2(p[t[0]], p[t[1]], p[t[2]]) / 2;
    EXPECT_GT(a, 0) << "zero-area or flipped triangle";
    sum += a;
  }
  return sum;
}

double PolygonArea(const std::vector<Point2>& p) {
  double sum = 0;
  for (size_t i = 0; i < p.size(); ++i) {
    const Point2& a = p[i];
    const Point2& b = p[(i + 1) % p.size()];
    sum += a.x * b.y - a.y * b.x;
  }
  return sum / 2;
}

TEST(EarClipTest, ConcavePolygonIsCoveredExactly) {
  const std::vector<Point2> l = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
  const EarClipResult r = EarClip(l);
  EXPECT_TRUE(r.simple);
  EXPECT_EQ(r.triangles.size(), 4u);
  EXPECT_NEAR(TriangulatedArea(l, r), 3.0, 1e-12);
}

TEST(EarClipTest, CombIsCoveredExactly) {
  std::vector<Point2> p;  // a comb: a strongly concave polygon
  for (int i = 0; i < 10; ++i) {
    p.push_back({static_cast<double>(i), 0});
  }
  p.push_back({10, 0});
  for (int i = 10; i > 0; --i) {
    p.push_back({static_cast<double>(i), 3});
    p.push_back({i - 0.5, 1});
  }
  p.push_back({0, 3});
  const EarClipResult r = EarClip(p);
  EXPECT_TRUE(r.simple);
  EXPECT_EQ(r.triangles.size(), p.size() - 2);  // straight corners are used, never clipped
  EXPECT_NEAR(TriangulatedArea(p, r), PolygonArea(p), 1e-9);
}

TEST(EarClipTest, CornersOnStraightEdgesAreKeptWithoutSlivers) {
  // A square with extra corners on two edges, as a patch with T-vertices.
  const std::vector<Point2> p = {{0, 0}, {0.5, 0}, {1, 0}, {1, 1}, {0.25, 1}, {0, 1}};
  const EarClipResult r = EarClip(p);
  EXPECT_EQ(r.triangles.size(), 4u);
  EXPECT_NEAR(TriangulatedArea(p, r), 1.0, 1e-12);
}

TEST(EarClipTest, PrefersWellShapedEars) {
  // A thin rhombus: the short diagonal makes the better triangles.
  const std::vector<Point2> p = {{0, 0}, {5, 1}, {10, 0}, {5, -1}};
  std::vector<Point2> ccw(p.rbegin(), p.rend());
  const EarClipResult r = EarClip(ccw);
  ASSERT_EQ(r.triangles.size(), 2u);
  for (const auto& t : r.triangles) {
    const bool uses_short = (ccw[t[0]].x == 5 || ccw[t[1]].x == 5 || ccw[t[2]].x == 5);
    EXPECT_TRUE(uses_short);
  }
  // Both triangles contain both x = 5 corners: the diagonal is the short one.
  int with_both = 0;
  for (const auto& t : r.triangles) {
    int fives = 0;
    for (uint32_t i : t) fives += ccw[i].x == 5;
    with_both += fives == 2;
  }
  EXPECT_EQ(with_both, 2);
}

TEST(EarClipTest, RegularPolygonIsDeterministic) {
  std::vector<Point2> p;
  for (int i = 0; i < 12; ++i) {
    const double a = 2 * std::numbers::pi * i / 12;
    p.push_back({std::cos(a), std::sin(a)});
  }
  const EarClipResult a = EarClip(p), b = EarClip(p);
  EXPECT_EQ(a.triangles, b.triangles);
  EXPECT_NEAR(TriangulatedArea(p, a), PolygonArea(p), 1e-12);
}

TEST(EarClipTest, SelfIntersectionIsReported) {
  // Self-intersecting, with no valid ear at the start: clipped anyway, and flagged.
  const std::vector<Point2> p = {{0, 3}, {1, 3}, {2, 1}, {0, 4}, {0, 2}, {2, 3}};
  const EarClipResult r = EarClip(p);
  EXPECT_FALSE(r.simple);
  EXPECT_FALSE(r.triangles.empty());
}

}  // namespace
}  // namespace radfarm
