// UvRaster: triangles drawn into a lightmap in their UV space (glTF convention: u across, v down
// from the top-left corner, so texel (x, y) has its centre at ((x + 0.5) / width, (y + 0.5) /
// height)). A texel belongs to the triangle its centre lies in, with the values at the three
// corners interpolated linearly; centres on a shared edge go to one triangle only (the top-left
// rule, on UVs snapped to 1/256 of a texel, so it is exact). Dilate then fills a gutter around the
// covered texels, so bilinear filtering at a UV seam reads light instead of black.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/rgb.h"
#include "output/image.h"

namespace radfarm {

using Uv = std::array<float, 2>;

struct UvRasterStats {
  uint64_t triangles = 0;
  uint64_t degenerate = 0;  // zero or non-finite UV area: drawn nowhere
  uint64_t covered = 0;     // texels some triangle covers
  uint64_t overlapped = 0;  // texels a second triangle covered too (overlapping UVs); first wins
  uint64_t dilated = 0;     // gutter texels Dilate filled
};

class UvRaster {
 public:
  UvRaster(uint32_t width, uint32_t height);

  // Draws one triangle; texels outside [0, 1)^2 are clipped.
  void Draw(const std::array<Uv, 3>& uv, const std::array<Rgb, 3>& value);

  // `texels` passes: each fills every empty texel beside (8-neighbours) a filled one with the mean
  // of those neighbours.
  void Dilate(int texels);

  const Image& image() const { return image_; }
  bool Covered(uint32_t x, uint32_t y) const { return state_[Index(x, y)] != kEmpty; }
  const UvRasterStats& stats() const { return stats_; }

 private:
  enum : uint8_t { kEmpty = 0, kDrawn = 1, kDilated = 2 };
  size_t Index(uint32_t x, uint32_t y) const { return size_t{y} * image_.width + x; }

  Image image_;
  std::vector<uint8_t> state_;
  UvRasterStats stats_;
};

}  // namespace radfarm
