// MakeLightmapCharts: coplanar triangles sharing edges make one chart, flattened without stretch;
// a fold, a facing flipped or a gap starts another.
#include "output/lightmap_charts.h"

#include <gtest/gtest.h>

#include <cmath>

namespace radfarm {
namespace {

double Distance(const FlatPoint& a, const FlatPoint& b) {
  return std::hypot(a[0] - b[0], a[1] - b[1]);
}

// Every edge keeps its length: the flattening is an isometry of each triangle.
void ExpectIsometric(const std::vector<std::array<Vec3, 3>>& triangles, const LightmapCharts& c) {
  for (size_t t = 0; t < triangles.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(Distance(c.flat[t][k], c.flat[t][(k + 1) % 3]),
                  Length(triangles[t][(k + 1) % 3] - triangles[t][k]), 1e-9)
          << "triangle " << t << " edge " << k;
    }
  }
}

// A box without its bottom: 5 faces of 2 triangles each, facing out.
std::vector<std::array<Vec3, 3>> OpenBox() {
  const Vec3 p[8] = {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0},
                     {0, 0, 3}, {2, 0, 3}, {2, 1, 3}, {0, 1, 3}};
  const int quads[5][4] = {{4, 5, 6, 7}, {0, 3, 2, 1}, {0, 1, 5, 4}, {1, 2, 6, 5}, {3, 7, 6, 2}};
  std::vector<std::array<Vec3, 3>> out;
  for (const auto& q : quads) {
    out.push_back({p[q[0]], p[q[1]], p[q[2]]});
    out.push_back({p[q[0]], p[q[2]], p[q[3]]});
  }
  return out;
}

TEST(LightmapChartsTest, EachPlaneOfABoxIsOneChartAndKeepsItsShape) {
  const auto box = OpenBox();
  const LightmapCharts c = MakeLightmapCharts(box);
  EXPECT_EQ(c.count, 5u);
  for (size_t t = 0; t < box.size(); t += 2) {
    EXPECT_EQ(c.chart[t], c.chart[t + 1]) << t;  // the two triangles of one face
    // Their shared corners land on the same flat points: one piece, no seam inside.
    EXPECT_NEAR(Distance(c.flat[t][0], c.flat[t + 1][0]), 0, 1e-12);
    EXPECT_NEAR(Distance(c.flat[t][2], c.flat[t + 1][1]), 0, 1e-12);
  }
  ExpectIsometric(box, c);
}

TEST(LightmapChartsTest, ABentStripIsCutWhereItBends) {
  // Two triangles sharing an edge at 1e-3 radians to each other: not one plane.
  const double tilt = 1e-3;
  const std::vector<std::array<Vec3, 3>> strip = {
      {Vec3{0, 0, 0}, Vec3{1, 0, 0}, Vec3{0, 1, 0}},
      {Vec3{1, 0, 0}, Vec3{1, 1, std::sin(tilt)}, Vec3{0, 1, 0}}};
  const LightmapCharts c = MakeLightmapCharts(strip);
  EXPECT_EQ(c.count, 2u);
  ExpectIsometric(strip, c);
}

TEST(LightmapChartsTest, TrianglesFacingOppositeWaysOrApartAreSeparateCharts) {
  const std::vector<std::array<Vec3, 3>> triangles = {
      {Vec3{0, 0, 0}, Vec3{1, 0, 0}, Vec3{0, 1, 0}},
      {Vec3{1, 0, 0}, Vec3{0, 1, 0}, Vec3{1, 1, 0}},   // shares the edge, faces down
      {Vec3{5, 0, 0}, Vec3{6, 0, 0}, Vec3{5, 1, 0}}};  // same plane, no shared edge
  const LightmapCharts c = MakeLightmapCharts(triangles);
  EXPECT_EQ(c.count, 3u);
  ExpectIsometric(triangles, c);
}

TEST(LightmapChartsTest, ADegenerateTriangleIsAChartOfItsOwn) {
  const std::vector<std::array<Vec3, 3>> triangles = {
      {Vec3{0, 0, 0}, Vec3{1, 0, 0}, Vec3{0, 1, 0}},
      {Vec3{1, 0, 0}, Vec3{0, 1, 0}, Vec3{0.5, 0.5, 0}}};
  const LightmapCharts c = MakeLightmapCharts(triangles);
  EXPECT_EQ(c.count, 2u);
  EXPECT_NE(c.chart[0], c.chart[1]);
}

}  // namespace
}  // namespace radfarm
