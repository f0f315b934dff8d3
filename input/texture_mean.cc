#include "input/texture_mean.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace radfarm {
namespace {

double SrgbToLinear(double v) {
  return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
}

// Texel index along one axis for texture coordinate u (in texture widths) on `size` texels.
uint32_t Wrap(double u, uint32_t size, TextureWrap wrap) {
  double x = u * size;
  const double n = size;
  switch (wrap) {
    case TextureWrap::kClampToEdge:
      x = std::clamp(x, 0.0, n - 1);
      break;
    case TextureWrap::kRepeat:
      x -= n * std::floor(x / n);
      break;
    case TextureWrap::kMirroredRepeat: {
      x -= 2 * n * std::floor(x / (2 * n));  // in [0, 2n)
      if (x >= n) x = 2 * n - x - 1e-9;
      break;
    }
  }
  const auto i = static_cast<int64_t>(std::floor(x));
  return static_cast<uint32_t>(std::clamp<int64_t>(i, 0, int64_t{size} - 1));
}

// sRGB code value to linear, one table per bit depth: 65536 pow() calls at most, once.
const std::vector<double>& LinearTable(int bits) {
  static const auto make = [](int levels) {
    std::vector<double> table(levels);
    for (int i = 0; i < levels; ++i) table[i] = SrgbToLinear(i / double(levels - 1));
    return table;
  };
  static const std::vector<double> eight = make(256);
  static const std::vector<double> sixteen = make(65536);
  return bits == 8 ? eight : sixteen;
}

Rgb TexelAt(const LinearTexture& t, double u, double v) {
  return t.Texel(Wrap(u, t.width, t.wrap_s), Wrap(v, t.height, t.wrap_t));
}

}  // namespace

bool LinearTexture::Readable() const {
  if (width == 0 || height == 0 || channels < 1 || channels > 4 || (bits != 8 && bits != 16)) {
    return false;
  }
  const uint64_t needed = uint64_t{width} * height * static_cast<uint64_t>(channels) * (bits / 8);
  return pixels.size() >= needed;
}

Rgb LinearTexture::Texel(uint32_t x, uint32_t y) const {
  const std::vector<double>& linear = LinearTable(bits);
  const size_t bytes = static_cast<size_t>(bits / 8);
  const unsigned char* p =
      pixels.data() + (static_cast<size_t>(y) * width + x) * static_cast<size_t>(channels) * bytes;
  auto channel = [&](int k) {
    const unsigned char* c = p + static_cast<size_t>(k) * bytes;
    return linear[bits == 8 ? c[0] : (c[0] | c[1] << 8)];  // 16-bit: little-endian from stb
  };
  if (channels < 3) {
    const double g = channel(0);
    return Rgb(g, g, g);
  }
  return Rgb(channel(0), channel(1), channel(2));
}

Rgb MeanOverTriangle(const LinearTexture& texture, const std::array<double, 2>& a,
                     const std::array<double, 2>& b, const std::array<double, 2>& c) {
  if (!texture.Readable()) return Rgb(0, 0, 0);
  // The triangle's area in texels decides n: n^2 samples for about that many texels.
  const double area = 0.5 *
                      std::fabs((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1])) *
                      texture.width * texture.height;
  const double wanted =
      std::clamp(std::isfinite(area) ? area : 0.0, 1.0, static_cast<double>(kMaxTextureSamples));
  const auto n = static_cast<uint32_t>(std::max(1.0, std::ceil(std::sqrt(wanted))));
  Rgb sum(0, 0, 0);
  uint64_t samples = 0;
  // Sub-triangles of the n x n subdivision, in barycentric steps of 1/n: for each row i and
  // column j the upward triangle, and the downward one beside it where there is room.
  auto add = [&](double s, double t) {  // s, t: barycentric weights of b and c
    const double u = a[0] + s * (b[0] - a[0]) + t * (c[0] - a[0]);
    const double v = a[1] + s * (b[1] - a[1]) + t * (c[1] - a[1]);
    sum += TexelAt(texture, u, v);
    ++samples;
  };
  for (uint32_t i = 0; i < n; ++i) {
    for (uint32_t j = 0; i + j < n; ++j) {
      add((i + 1.0 / 3) / n, (j + 1.0 / 3) / n);
      if (i + j + 1 < n) add((i + 2.0 / 3) / n, (j + 2.0 / 3) / n);
    }
  }
  return sum / static_cast<double>(samples);
}

}  // namespace radfarm
