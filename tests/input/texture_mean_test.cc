#include "input/texture_mean.h"

#include <gtest/gtest.h>

#include <vector>

namespace radfarm {
namespace {

LinearTexture View(const std::vector<unsigned char>& pixels, uint32_t width, uint32_t height,
                   int channels, int bits = 8) {
  LinearTexture t;
  t.width = width;
  t.height = height;
  t.channels = channels;
  t.bits = bits;
  t.pixels = pixels;
  return t;
}

TEST(TextureMeanTest, ReadsSrgbAsLinear) {
  const std::vector<unsigned char> rgb = {0, 128, 255};
  const Rgb texel = View(rgb, 1, 1, 3).Texel(0, 0);
  EXPECT_DOUBLE_EQ(texel.r, 0);
  EXPECT_NEAR(texel.g, 0.2158605, 1e-6);
  EXPECT_DOUBLE_EQ(texel.b, 1);
  // 16-bit, little-endian, grey + alpha: the grey in all three channels.
  const std::vector<unsigned char> grey16 = {0xFF, 0xFF, 0, 0};
  EXPECT_DOUBLE_EQ(View(grey16, 1, 1, 2, 16).Texel(0, 0).g, 1);
}

TEST(TextureMeanTest, RefusesShortPixelDataAndUnknownLayouts) {
  const std::vector<unsigned char> two = {0, 0};
  EXPECT_FALSE(View(two, 1, 1, 3).Readable());
  EXPECT_FALSE(View(two, 1, 1, 5).Readable());
  EXPECT_FALSE(View(two, 1, 1, 1, 12).Readable());
  EXPECT_TRUE(View(two, 1, 1, 2).Readable());
}

// Left half 1, right half 0: over the UV triangle (0,0) (1,0) (0,1) the left half's share of the
// area is 1 - 0.5^2 / ... = 3/4 exactly; the sampled mean is within a sample row of it.
TEST(TextureMeanTest, MeanOverATriangleIsItsAreaShare) {
  std::vector<unsigned char> grey(256, 0);
  for (uint32_t x = 0; x < 128; ++x) grey[x] = 255;
  const Rgb mean = MeanOverTriangle(View(grey, 256, 1, 1), {0, 0}, {1, 0}, {0, 1});
  EXPECT_NEAR(mean.r, 0.75, 0.01);
}

TEST(TextureMeanTest, WrapModesRepeatMirrorAndClamp) {
  const std::vector<unsigned char> grey = {255, 0};
  LinearTexture t = View(grey, 2, 1, 1);
  // A tiny triangle around u = 1.25: repeat reads texel 0 (u 0.25), mirror texel 1 (u 0.75),
  // clamp the last texel.
  const std::array<double, 2> a{1.24, 0.5}, b{1.26, 0.5}, c{1.25, 0.51};
  EXPECT_DOUBLE_EQ(MeanOverTriangle(t, a, b, c).r, 1);
  t.wrap_s = TextureWrap::kMirroredRepeat;
  EXPECT_DOUBLE_EQ(MeanOverTriangle(t, a, b, c).r, 0);
  t.wrap_s = TextureWrap::kClampToEdge;
  EXPECT_DOUBLE_EQ(MeanOverTriangle(t, a, b, c).r, 0);
}

}  // namespace
}  // namespace radfarm
