// The mean colour of a texture over a triangle of UV space: what a patch cut from that triangle
// reflects on average (a textured floor bleeds its mean colour onto the walls).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/rgb.h"

namespace radfarm {

enum class TextureWrap { kRepeat, kClampToEdge, kMirroredRepeat };

// A decoded image in linear RGB (sRGB decoded), row-major, top row first (glTF's v = 0 is the top).
struct LinearTexture {
  uint32_t width = 0;
  uint32_t height = 0;
  std::vector<Rgb> texels;
  TextureWrap wrap_s = TextureWrap::kRepeat;
  TextureWrap wrap_t = TextureWrap::kRepeat;
};

// 8- or 16-bit sRGB-encoded pixels of 1 to 4 channels (grey, grey + alpha, RGB, RGBA; alpha is
// ignored) decoded to linear RGB. `bytes` holds width * height * channels * bits / 8 bytes.
LinearTexture DecodeSrgbTexture(const std::vector<unsigned char>& bytes, uint32_t width,
                                uint32_t height, int channels, int bits);

// The mean over the UV triangle (a, b, c) of the texture, nearest texel, wrapped: the average of
// the texels at the centroids of a regular subdivision of the triangle into n^2 equal triangles,
// n growing with the triangle's size in texels (so every texel it covers is sampled about once,
// up to kMaxTextureSamples samples). Deterministic; exact for a texture constant over the triangle.
Rgb MeanOverTriangle(const LinearTexture& texture, const std::array<double, 2>& a,
                     const std::array<double, 2>& b, const std::array<double, 2>& c);

inline constexpr uint64_t kMaxTextureSamples = 1 << 16;

}  // namespace radfarm
