#include "mesh/polygon.h"

#include <gtest/gtest.h>

#include <random>

#include "mesh/point_grid.h"

namespace radfarm {
namespace {

const std::vector<Vec3> kLShape = {{0, 0, 0}, {2, 0, 0}, {2, 1, 0},
                                   {1, 1, 0}, {1, 2, 0}, {0, 2, 0}};

TEST(PolygonTest, VectorAreaOfLShapeIsItsAreaAlongTheNormal) {
  const Vec3 a = VectorArea(kLShape);
  EXPECT_DOUBLE_EQ(a.z, 3.0);
  EXPECT_DOUBLE_EQ(a.x, 0.0);
  EXPECT_DOUBLE_EQ(a.y, 0.0);
}

TEST(PolygonTest, VectorAreaKeepsPrecisionFarFromTheOrigin) {
  std::vector<Vec3> far;
  for (const Vec3& p : kLShape) far.push_back(p + Vec3{1e9, -1e9, 1e9});
  EXPECT_NEAR(VectorArea(far).z, 3.0, 1e-6);
}

TEST(PolygonTest, AreaCentroidOfConcavePolygon) {
  // Three unit squares: (0.5, 0.5), (1.5, 0.5), (0.5, 1.5).
  const Vec3 c = AreaCentroid(kLShape);
  EXPECT_NEAR(c.x, 2.5 / 3, 1e-12);
  EXPECT_NEAR(c.y, 2.5 / 3, 1e-12);
}

TEST(PolygonTest, ConvexityAndPlanarity) {
  const Vec3 up{0, 0, 1};
  EXPECT_FALSE(IsStrictlyConvex(kLShape, up));
  EXPECT_TRUE(IsStrictlyConvex({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, up));
  EXPECT_FALSE(IsStrictlyConvex({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, -up));
  EXPECT_NEAR(MaxPlaneDistance({{0, 0, 0}, {1, 0, 0}, {1, 1, 0.4}, {0, 1, 0}}, up), 0.3, 1e-12);
}

TEST(PolygonTest, RemovesRepeatedStraightAndSpikeCorners) {
  std::vector<Vec3> p = {{0, 0, 0}, {0, 0, 0},   {1, 0, 0}, {2, 0, 0},  // repeat, straight
                         {2, 2, 0}, {2, 3, 0},   {2, 2, 0},             // spike out and back
                         {0, 2, 0}, {0, 1e-9, 0}};                      // near repeat
  RemoveRedundantCorners(1e-6, &p);
  ASSERT_EQ(p.size(), 4u);
  EXPECT_NEAR(VectorArea(p).z, 4.0, 1e-8);  // (0, 0) or its near repeat may stay
}

TEST(PolygonTest, CollinearPolygonVanishes) {
  std::vector<Vec3> p = {{0, 0, 0}, {1, 1, 1}, {3, 3, 3}};
  RemoveRedundantCorners(1e-6, &p);
  EXPECT_TRUE(p.empty());
}

TEST(PolygonTest, ProjectionKeepsCounterClockwise) {
  const Vec3 n = Normalize({1, 2, 3});
  Vec3 t, b;
  OrthonormalBasis(n, &t, &b);
  const std::vector<Vec3> tri = {{0, 0, 0}, t, b};  // counter-clockwise about n
  const std::vector<Point2> q = ProjectToPlane(tri, {0, 0, 0}, n);
  EXPECT_GT(Orient2(q[0], q[1], q[2]), 0);
}

// InBox: the points inside, bounds included, ascending; a box larger than the grid's cells visits
// the occupied cells instead, with the same answer; an empty box finds nothing.
TEST(PointGridTest, FindsThePointsInABox) {
  PointGrid grid(0.5);
  for (int i = 0; i < 10; ++i) grid.Add({double(i), 0.5 * i, -double(i)});
  Bounds3 box;
  box.Extend({2, 1, -6});
  box.Extend({6, 3, -2});
  EXPECT_EQ(grid.InBox(box), (std::vector<uint32_t>{2, 3, 4, 5, 6}));
  Bounds3 huge;
  huge.Extend({-1e30, -1e30, -1e30});
  huge.Extend({1e30, 1e30, 1e30});
  EXPECT_EQ(grid.InBox(huge).size(), 10u);
  EXPECT_TRUE(grid.InBox(Bounds3{}).empty());
}

TEST(PointGridTest, FindsPointsNearLongSegmentsAcrossManyCells) {
  PointGrid grid(0.1);
  grid.Add({0.5, 0.5, 0.5});   // 0: on the segment
  grid.Add({0.5, 0.55, 0.5});  // 1: 0.05 away
  grid.Add({0.9, 0.9, 0.9});   // 2: on the segment, near its end
  grid.Add({1.2, 1.2, 1.2});   // 3: beyond the end
  const std::vector<uint32_t> near = grid.NearSegment({0, 0, 0}, {1, 1, 1}, 0.01);
  EXPECT_EQ(near, (std::vector<uint32_t>{0, 2}));
  EXPECT_EQ(grid.NearSegment({0, 0, 0}, {1, 1, 1}, 0.05).size(), 3u);
}

// FirstNear is NearSegment(p, p, tol).front() without the list: the lowest id within tol, across
// the cell borders of a fine grid, several points to a cell, and nothing where none is near.
TEST(PointGridTest, FirstNearIsTheLowestIdWithinTheTolerance) {
  PointGrid grid(0.05);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  for (int i = 0; i < 4000; ++i) grid.Add({u(rng), u(rng), 0.1 * u(rng)});
  int found = 0;
  for (int q = 0; q < 2000; ++q) {
    const Vec3 p{u(rng), u(rng), 0.1 * u(rng)};
    const double tol = q % 2 ? 0.01 : 0.12;  // within a cell, and across several
    const std::vector<uint32_t> near = grid.NearSegment(p, p, tol);
    ASSERT_EQ(grid.FirstNear(p, tol), near.empty() ? PointGrid::kNone : near.front()) << q;
    found += !near.empty();
  }
  EXPECT_GT(found, 500);
  EXPECT_LT(found, 2000);
}

// Cells are counted from the first point in 32 bits: points a trillion cells away share the
// clamped border cells, and every query still finds what a brute-force search finds.
TEST(PointGridTest, FarPointsShareBorderCellsAndAreStillFound) {
  PointGrid grid(1e-3);
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Vec3> points;
  for (int i = 0; i < 3000; ++i) {
    const Vec3 base = i % 3 == 0   ? Vec3{0, 0, 0}
                      : i % 3 == 1 ? Vec3{1e9, -1e9, 5}
                                   : Vec3{-1e9, 0, 1e9};
    points.push_back(base + Vec3{u(rng), u(rng), u(rng)} * 0.05);
    grid.Add(points.back());
  }
  for (int q = 0; q < 600; ++q) {
    const Vec3 p = points[q * 5] + Vec3{u(rng), u(rng), u(rng)} * 0.004;
    const double tol = 0.005;
    uint32_t brute = PointGrid::kNone;
    for (uint32_t id = 0; id < points.size() && brute == PointGrid::kNone; ++id) {
      if (DistanceToSegment(points[id], p, p) <= tol) brute = id;
    }
    ASSERT_EQ(grid.FirstNear(p, tol), brute) << q;
  }
}

TEST(PointWelderTest, FirstPointOfAClusterStandsForIt) {
  PointWelder welder(1e-6);
  EXPECT_EQ(welder.Weld({1, 2, 3}), 0u);
  EXPECT_EQ(welder.Weld({1, 2, 3 + 5e-7}), 0u);
  EXPECT_EQ(welder.Weld({1, 2, 3 + 5e-6}), 1u);
  EXPECT_EQ(welder.point(0).z, 3.0);
}

}  // namespace
}  // namespace radfarm
