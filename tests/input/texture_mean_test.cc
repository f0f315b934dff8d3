#include "input/texture_mean.h"

#include <gtest/gtest.h>

namespace radfarm {
namespace {

TEST(TextureMeanTest, DecodesSrgbToLinear) {
  const LinearTexture t = DecodeSrgbTexture({0, 128, 255}, 1, 1, 3, 8);
  ASSERT_EQ(t.texels.size(), 1u);
  EXPECT_DOUBLE_EQ(t.texels[0].r, 0);
  EXPECT_NEAR(t.texels[0].g, 0.2158605, 1e-6);
  EXPECT_DOUBLE_EQ(t.texels[0].b, 1);
}

TEST(TextureMeanTest, RefusesShortPixelData) {
  EXPECT_EQ(DecodeSrgbTexture({0, 0}, 1, 1, 3, 8).width, 0u);
}

// Left half 1, right half 0: over the UV triangle (0,0) (1,0) (0,1) the left half's share of the
// area is 1 - 0.5^2 / ... = 3/4 exactly; the sampled mean is within a sample row of it.
TEST(TextureMeanTest, MeanOverATriangleIsItsAreaShare) {
  LinearTexture t;
  t.width = 256;
  t.height = 1;
  t.texels.resize(256);
  for (uint32_t x = 0; x < 128; ++x) t.texels[x] = Rgb(1, 1, 1);
  const Rgb mean = MeanOverTriangle(t, {0, 0}, {1, 0}, {0, 1});
  EXPECT_NEAR(mean.r, 0.75, 0.01);
}

TEST(TextureMeanTest, WrapModesRepeatMirrorAndClamp) {
  LinearTexture t;
  t.width = 2;
  t.height = 1;
  t.texels = {Rgb(1, 1, 1), Rgb(0, 0, 0)};
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
