// UvRaster: which texel centres a triangle covers (half-open at shared edges, exactly), values
// interpolated linearly, the gutter Dilate fills, degenerate and overlapping UVs counted.
#include "output/uv_raster.h"

#include <gtest/gtest.h>

#include <cmath>

namespace radfarm {
namespace {

constexpr Rgb kRed(1, 0, 0), kGreen(0, 1, 0), kBlue(0, 0, 1);

// The unit square as two triangles sharing the diagonal (0,0)-(1,1).
void DrawSquare(UvRaster* raster, const Rgb& value) {
  raster->Draw({Uv{0, 0}, Uv{1, 0}, Uv{1, 1}}, {value, value, value});
  raster->Draw({Uv{0, 0}, Uv{1, 1}, Uv{0, 1}}, {value, value, value});
}

TEST(UvRasterTest, TwoTrianglesSharingAnEdgeCoverEveryTexelOnce) {
  UvRaster raster(16, 16);
  DrawSquare(&raster, Rgb(1, 1, 1));
  // The diagonal passes through 16 texel centres: each goes to one of the two triangles.
  EXPECT_EQ(raster.stats().covered, 256u);
  EXPECT_EQ(raster.stats().overlapped, 0u);
  for (uint32_t y = 0; y < 16; ++y) {
    for (uint32_t x = 0; x < 16; ++x) EXPECT_TRUE(raster.Covered(x, y)) << x << "," << y;
  }
}

TEST(UvRasterTest, CoversTheTexelCentresInsideOnly) {
  // A right triangle over texels 0..3 of an 8 x 8 map. Centres on its hypotenuse, (x + 0.5) +
  // (y + 0.5) = 4, belong to the triangle beyond it (the top-left rule): only those below count.
  UvRaster raster(8, 8);
  raster.Draw({Uv{0, 0}, Uv{0.5f, 0}, Uv{0, 0.5f}}, {kRed, kRed, kRed});
  uint64_t expected = 0;
  for (uint32_t y = 0; y < 8; ++y) {
    for (uint32_t x = 0; x < 8; ++x) {
      const bool inside = (x + 0.5) + (y + 0.5) < 4;
      expected += inside;
      EXPECT_EQ(raster.Covered(x, y), inside) << x << "," << y;
    }
  }
  EXPECT_EQ(raster.stats().covered, expected);
}

TEST(UvRasterTest, InterpolatesTheCornersLinearly) {
  // Corners red, green, blue at (0,0), (1,0), (0,1): a texel centre (u, v) has weights
  // (1 - u - v, u, v).
  UvRaster raster(10, 10);
  raster.Draw({Uv{0, 0}, Uv{1, 0}, Uv{0, 1}}, {kRed, kGreen, kBlue});
  for (uint32_t y = 0; y < 10; ++y) {
    for (uint32_t x = 0; x + y < 9; ++x) {
      const double u = (x + 0.5) / 10, v = (y + 0.5) / 10;
      const Rgb& got = raster.image().At(x, y);
      EXPECT_NEAR(got.r, 1 - u - v, 1e-6);
      EXPECT_NEAR(got.g, u, 1e-6);
      EXPECT_NEAR(got.b, v, 1e-6);
    }
  }
}

TEST(UvRasterTest, EitherWindingDrawsTheSame) {
  UvRaster a(12, 12), b(12, 12);
  a.Draw({Uv{0.1f, 0.1f}, Uv{0.9f, 0.2f}, Uv{0.3f, 0.8f}}, {kRed, kGreen, kBlue});
  b.Draw({Uv{0.1f, 0.1f}, Uv{0.3f, 0.8f}, Uv{0.9f, 0.2f}}, {kRed, kBlue, kGreen});
  EXPECT_GT(a.stats().covered, 0u);
  EXPECT_EQ(a.stats().covered, b.stats().covered);
  for (size_t i = 0; i < a.image().pixels.size(); ++i) {
    EXPECT_NEAR(a.image().pixels[i].r, b.image().pixels[i].r, 1e-12);
    EXPECT_NEAR(a.image().pixels[i].b, b.image().pixels[i].b, 1e-12);
  }
}

TEST(UvRasterTest, DegenerateTrianglesDrawNothing) {
  UvRaster raster(8, 8);
  raster.Draw({Uv{0.2f, 0.2f}, Uv{0.2f, 0.2f}, Uv{0.7f, 0.7f}},
              {kRed, kRed, kRed});                                        // a point twice
  raster.Draw({Uv{0, 0}, Uv{0.5f, 0.5f}, Uv{1, 1}}, {kRed, kRed, kRed});  // a line
  raster.Draw({Uv{NAN, 0}, Uv{1, 0}, Uv{0, 1}}, {kRed, kRed, kRed});      // not finite
  EXPECT_EQ(raster.stats().triangles, 3u);
  EXPECT_EQ(raster.stats().degenerate, 3u);
  EXPECT_EQ(raster.stats().covered, 0u);
}

TEST(UvRasterTest, ClipsUvsOutsideTheUnitSquare) {
  UvRaster raster(4, 4);
  raster.Draw({Uv{-3, -3}, Uv{5, -3}, Uv{-3, 5}}, {kRed, kRed, kRed});
  EXPECT_EQ(raster.stats().covered, 16u);
}

TEST(UvRasterTest, CountsOverlapsAndKeepsTheFirst) {
  UvRaster raster(8, 8);
  DrawSquare(&raster, kRed);
  raster.Draw({Uv{0, 0}, Uv{0.5f, 0}, Uv{0, 0.5f}}, {kGreen, kGreen, kGreen});
  EXPECT_EQ(raster.stats().covered, 64u);
  EXPECT_EQ(raster.stats().overlapped, 6u);  // the centres with x + y < 3
  EXPECT_EQ(raster.image().At(0, 0), kRed);
}

TEST(UvRasterTest, DilateFillsTheGutterFromTheIsland) {
  // An island of 2 x 2 texels in the middle of a 10 x 10 map, each texel a different value.
  UvRaster raster(10, 10);
  raster.Draw({Uv{0.4f, 0.4f}, Uv{0.6f, 0.4f}, Uv{0.6f, 0.6f}}, {kRed, kRed, kRed});
  raster.Draw({Uv{0.4f, 0.4f}, Uv{0.6f, 0.6f}, Uv{0.4f, 0.6f}}, {kRed, kRed, kRed});
  ASSERT_EQ(raster.stats().covered, 4u);
  raster.Dilate(2);
  // Two passes reach texels within Chebyshev distance 2 of the island: x, y in [2, 7].
  for (uint32_t y = 0; y < 10; ++y) {
    for (uint32_t x = 0; x < 10; ++x) {
      const bool reached = x >= 2 && x <= 7 && y >= 2 && y <= 7;
      EXPECT_EQ(raster.Covered(x, y), reached) << x << "," << y;
      if (reached) {
        EXPECT_EQ(raster.image().At(x, y), kRed) << x << "," << y;
      }
    }
  }
  EXPECT_EQ(raster.stats().dilated, 36u - 4u);
}

TEST(UvRasterTest, DilateAveragesTheNeighboursOfTwoIslands) {
  // Two single-texel islands, red at x = 0 and blue at x = 2 of a 3 x 1 map: the texel between
  // them gets their mean, so bilinear filtering across the gap reads no black.
  UvRaster raster(3, 1);
  raster.Draw({Uv{0, 0}, Uv{2 / 3.f, 0}, Uv{0, 1}}, {kRed, kRed, kRed});
  raster.Draw({Uv{1, 0}, Uv{1, 1}, Uv{2 / 3.f, 1}}, {kBlue, kBlue, kBlue});
  ASSERT_TRUE(raster.Covered(0, 0));
  ASSERT_TRUE(raster.Covered(2, 0));
  ASSERT_FALSE(raster.Covered(1, 0));
  raster.Dilate(1);
  EXPECT_EQ(raster.image().At(1, 0), Rgb(0.5, 0, 0.5));
}

}  // namespace
}  // namespace radfarm

namespace radfarm {
namespace {

// Bilinear at texel coordinates (x, y) (texel centres at i + 0.5), as a GPU samples.
double Bilinear(const Image& image, double x, double y) {
  x -= 0.5;
  y -= 0.5;
  const int x0 = int(std::floor(x)), y0 = int(std::floor(y));
  const double fx = x - x0, fy = y - y0;
  const auto at = [&](int xi, int yi) { return image.At(uint32_t(xi), uint32_t(yi)).r; };
  return (1 - fy) * ((1 - fx) * at(x0, y0) + fx * at(x0 + 1, y0)) +
         fy * ((1 - fx) * at(x0, y0 + 1) + fx * at(x0 + 1, y0 + 1));
}

TEST(UvRasterTest, ExtendStitchesASeamSoBothSidesReadTheSameValue) {
  // One square of a surface lit by the linear ramp L = 1 + 2 s + t over s, t in [0, 1], cut along
  // its diagonal into two islands placed apart in a 64 x 64 lightmap: the diagonal is a seam.
  const auto light = [](double s, double t) { return Rgb(1 + 2 * s + t, 0, 0); };
  const float side = 20.0f / 64;
  const Uv a0{4 / 64.f, 4 / 64.f}, b0{34 / 64.f, 8 / 64.f};  // the islands' (0, 0) corners
  UvRaster raster(64, 64);
  raster.Draw({Uv{a0[0], a0[1]}, Uv{a0[0] + side, a0[1]}, Uv{a0[0] + side, a0[1] + side}},
              {light(0, 0), light(1, 0), light(1, 1)});
  raster.Draw({Uv{b0[0], b0[1]}, Uv{b0[0] + side, b0[1] + side}, Uv{b0[0], b0[1] + side}},
              {light(0, 0), light(1, 1), light(0, 1)});
  raster.Extend(1.0);
  raster.Dilate(4);
  EXPECT_GT(raster.stats().extended, 0u);
  for (double f = 0.05; f < 1; f += 0.05) {  // points along the diagonal, in both islands
    const double ua = (a0[0] + f * side) * 64, va = (a0[1] + f * side) * 64;
    const double ub = (b0[0] + f * side) * 64, vb = (b0[1] + f * side) * 64;
    const double expected = light(f, f).r;
    EXPECT_NEAR(Bilinear(raster.image(), ua, va), expected, 1e-6 * expected) << f;
    EXPECT_NEAR(Bilinear(raster.image(), ub, vb), expected, 1e-6 * expected) << f;
  }
}

TEST(UvRasterTest, ExtendFillsOnlyNearTexelsAndClampsAtZero) {
  UvRaster raster(16, 16);
  // A steep ramp from 0 at the left: extended leftwards it would go negative.
  raster.Draw({Uv{0.25f, 0.25f}, Uv{0.75f, 0.25f}, Uv{0.25f, 0.75f}},
              {Rgb(0, 0, 0), Rgb(8, 8, 8), Rgb(0, 0, 0)});
  raster.Extend(1.0);
  EXPECT_FALSE(raster.Covered(1, 8));  // 2.5 texels out
  EXPECT_TRUE(raster.Covered(3, 8));   // 0.5 texels out
  EXPECT_EQ(raster.image().At(3, 8).r, 0.0);
  EXPECT_NEAR(raster.image().At(8, 3).r, 8.5 - 4, 1e-9);  // 0.5 above the top edge
}

}  // namespace
}  // namespace radfarm
