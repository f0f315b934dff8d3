// The mean colour of a texture over a triangle of UV space: what a patch cut from that triangle
// reflects on average (a textured floor bleeds its mean colour onto the walls).
#pragma once

#include <array>
#include <cstdint>
#include <span>

#include "core/rgb.h"

namespace radfarm {

enum class TextureWrap { kRepeat, kClampToEdge, kMirroredRepeat };

// A decoded image, read as linear RGB texel by texel: 8- or 16-bit sRGB-encoded channels, 1 to 4
// of them (grey, grey + alpha, RGB, RGBA; alpha is ignored), row-major, top row first (glTF's
// v = 0 is the top), 16-bit channels little-endian as stb_image gives them. The texture only views
// the decoded pixels: an image is held once, never also as a copy in another form.
struct LinearTexture {
  uint32_t width = 0;
  uint32_t height = 0;
  int channels = 3;
  int bits = 8;
  std::span<const unsigned char> pixels;  // not owned; must outlive the texture
  TextureWrap wrap_s = TextureWrap::kRepeat;
  TextureWrap wrap_t = TextureWrap::kRepeat;

  // Whether MeanOverTriangle can read it: a layout above, and width * height * channels * bits / 8
  // bytes of pixels at least.
  bool Readable() const;
  // The texel at column x, row y, in linear RGB.
  Rgb Texel(uint32_t x, uint32_t y) const;
};

// The mean over the UV triangle (a, b, c) of the texture, nearest texel, wrapped: the average of
// the texels at the centroids of a regular subdivision of the triangle into n^2 equal triangles,
// n growing with the triangle's size in texels (so every texel it covers is sampled about once,
// up to kMaxTextureSamples samples). Deterministic; exact for a texture constant over the triangle.
Rgb MeanOverTriangle(const LinearTexture& texture, const std::array<double, 2>& a,
                     const std::array<double, 2>& b, const std::array<double, 2>& c);

inline constexpr uint64_t kMaxTextureSamples = 1 << 16;

}  // namespace radfarm
