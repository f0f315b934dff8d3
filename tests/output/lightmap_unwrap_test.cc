// UnwrapLightmaps: every object's charts inside its own unit square, no two overlapping, a gutter
// of kChartGutter texels around each, texels of the size asked for, the fixed size kept.
#include "output/lightmap_unwrap.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "output/lightmap_writer.h"
#include "output/uv_raster.h"

namespace radfarm {
namespace {

// A closed box of 6 quads (12 triangles) as object `object`, corner at `at`, sides `s`.
void AddBox(uint32_t object, const Vec3& at, const Vec3& s, std::vector<LightmapTriangle>* out) {
  const Vec3 p[8] = {at,
                     at + Vec3{s.x, 0, 0},
                     at + Vec3{s.x, s.y, 0},
                     at + Vec3{0, s.y, 0},
                     at + Vec3{0, 0, s.z},
                     at + Vec3{s.x, 0, s.z},
                     at + Vec3{s.x, s.y, s.z},
                     at + Vec3{0, s.y, s.z}};
  const int quads[6][4] = {{4, 5, 6, 7}, {0, 3, 2, 1}, {0, 1, 5, 4},
                           {1, 2, 6, 5}, {3, 7, 6, 2}, {0, 4, 7, 3}};
  for (const auto& q : quads) {
    out->push_back({object, {p[q[0]], p[q[1]], p[q[2]]}, {}});
    out->push_back({object, {p[q[0]], p[q[2]], p[q[3]]}, {}});
  }
}

std::vector<InputObject> Objects(size_t n) {
  std::vector<InputObject> out(n);
  for (size_t i = 0; i < n; ++i) out[i].name = "object" + std::to_string(i);
  return out;
}

double WorldArea(const LightmapTriangle& t) {
  return 0.5 * Length(Cross(t.position[1] - t.position[0], t.position[2] - t.position[0]));
}

double UvArea(const LightmapTriangle& t) {
  return 0.5 * std::abs(double(t.uv[1][0] - t.uv[0][0]) * (t.uv[2][1] - t.uv[0][1]) -
                        double(t.uv[1][1] - t.uv[0][1]) * (t.uv[2][0] - t.uv[0][0]));
}

// The texels each object's triangles cover, with Extend's border ring: no texel twice, so charts
// and their stitched borders never overlap.
void ExpectNoOverlap(const UnwrappedLightmaps& u, uint32_t object) {
  const uint32_t side = u.size[object];
  UvRaster raster(side, side);
  for (const LightmapTriangle& t : u.triangles) {
    if (t.object != object) continue;
    for (const auto& uv : t.uv) {
      EXPECT_GE(uv[0], 0.0f);
      EXPECT_LE(uv[0], 1.0f);
      EXPECT_GE(uv[1], 0.0f);
      EXPECT_LE(uv[1], 1.0f);
    }
    raster.Draw(t.uv, {Rgb(1, 1, 1), Rgb(1, 1, 1), Rgb(1, 1, 1)});
  }
  EXPECT_EQ(raster.stats().overlapped, 0u);
  EXPECT_EQ(raster.stats().degenerate, 0u);
  EXPECT_GT(raster.stats().covered, 0u);
}

TEST(LightmapUnwrapTest, ChartsFitTheirSquareAtTheTexelAskedForWithoutOverlap) {
  std::vector<LightmapTriangle> triangles;
  AddBox(0, {0, 0, 0}, {4, 2, 3}, &triangles);
  AddBox(2, {10, 0, 0}, {1, 1, 1}, &triangles);
  const double texel = 0.05;
  const UnwrappedLightmaps u = UnwrapLightmaps(triangles, Objects(3), texel, 0, nullptr);
  ASSERT_EQ(u.triangles.size(), triangles.size());
  EXPECT_EQ(u.size[1], 0u);  // no triangles: no lightmap
  for (const uint32_t o : {0u, 2u}) {
    SCOPED_TRACE(o);
    EXPECT_EQ(u.size[o] % 4, 0u);
    EXPECT_GE(u.size[o], kMinLightmapSize);
    ExpectNoOverlap(u, o);
  }
  // The large box at the texel asked for: its UV area in texels is its area in texels squared.
  double world = 0, uv = 0;
  for (const LightmapTriangle& t : u.triangles) {
    if (t.object != 0) continue;
    world += WorldArea(t);
    uv += UvArea(t);
  }
  EXPECT_NEAR(uv * u.size[0] * u.size[0], world / (texel * texel), 1e-3 * world / (texel * texel));
}

TEST(LightmapUnwrapTest, ChartsAreKeptAGutterApart) {
  std::vector<LightmapTriangle> triangles;
  AddBox(0, {0, 0, 0}, {4, 2, 3}, &triangles);
  const UnwrappedLightmaps u = UnwrapLightmaps(triangles, Objects(1), 0.05, 0, nullptr);
  const double side = u.size[0];
  // Each face (two triangles) is a chart: its texel bounds, one apart from every other face's by
  // twice the gutter on some axis.
  std::vector<std::array<double, 4>> boxes;
  for (size_t t = 0; t < u.triangles.size(); t += 2) {
    std::array<double, 4> b = {INFINITY, INFINITY, -INFINITY, -INFINITY};
    for (size_t k = t; k < t + 2; ++k) {
      for (const auto& uv : u.triangles[k].uv) {
        b[0] = std::min(b[0], uv[0] * side);
        b[1] = std::min(b[1], uv[1] * side);
        b[2] = std::max(b[2], uv[0] * side);
        b[3] = std::max(b[3], uv[1] * side);
      }
    }
    EXPECT_GE(std::min(b[0], b[1]), kChartGutter - 1e-3);
    EXPECT_LE(std::max(b[2], b[3]), side - kChartGutter + 1e-3);
    boxes.push_back(b);
  }
  for (size_t i = 0; i < boxes.size(); ++i) {
    for (size_t j = i + 1; j < boxes.size(); ++j) {
      const double gap = std::max({boxes[j][0] - boxes[i][2], boxes[i][0] - boxes[j][2],
                                   boxes[j][1] - boxes[i][3], boxes[i][1] - boxes[j][3]});
      EXPECT_GE(gap, 2.0 * kChartGutter - 1e-3) << i << " " << j;
    }
  }
}

TEST(LightmapUnwrapTest, AFixedSizeIsKeptWithTheFinestTexelThatFits) {
  std::vector<LightmapTriangle> triangles;
  AddBox(0, {0, 0, 0}, {4, 2, 3}, &triangles);
  AddBox(1, {10, 0, 0}, {0.1, 0.1, 0.1}, &triangles);
  const UnwrappedLightmaps u = UnwrapLightmaps(triangles, Objects(2), 0.05, 64, nullptr);
  for (const uint32_t o : {0u, 1u}) {
    EXPECT_EQ(u.size[o], 64u);
    ExpectNoOverlap(u, o);
    double uv = 0;
    for (const LightmapTriangle& t : u.triangles) uv += t.object == o ? UvArea(t) : 0;
    // Most of the square is chart: the texel is near the finest that fits.
    EXPECT_GT(uv, 0.5) << o;
  }
}

TEST(LightmapUnwrapTest, GutterTexelsAreAFewPercentOfALargeChartsSquare) {
  std::vector<LightmapTriangle> triangles;
  AddBox(0, {0, 0, 0}, {4, 4, 4}, &triangles);
  // Faces of 160 texels: a one-texel gutter around each is about 2.5 % of the square.
  const UnwrappedLightmaps u = UnwrapLightmaps(triangles, Objects(1), 0.025, 0, nullptr);
  const double fraction = double(u.gutter_texels[0]) / (double(u.size[0]) * u.size[0]);
  EXPECT_LT(fraction, 0.05);
  EXPECT_GT(fraction, 0.0);
}

TEST(LightmapUnwrapTest, AnObjectWithoutAreaGetsNoLightmapAndNoWarning) {
  std::vector<LightmapTriangle> triangles = {
      {0, {Vec3{0, 0, 0}, Vec3{1, 0, 0}, Vec3{2, 0, 0}}, {}}};
  std::vector<std::string> warnings;
  const UnwrappedLightmaps u = UnwrapLightmaps(triangles, Objects(1), 0.05, 0, &warnings);
  EXPECT_EQ(u.size[0], 0u);
  EXPECT_EQ(warnings, std::vector<std::string>{});
}

}  // namespace
}  // namespace radfarm
