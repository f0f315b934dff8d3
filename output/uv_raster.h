// UvRaster: triangles drawn into a lightmap in their UV space (glTF convention: u across, v down
// from the top-left corner, so texel (x, y) has its centre at ((x + 0.5) / width, (y + 0.5) /
// height)). A texel belongs to the triangle its centre lies in, with the values at the three
// corners interpolated linearly; centres on a shared edge go to one triangle only (the top-left
// rule, on UVs snapped to 1/256 of a texel, so it is exact). Extend then stitches the islands'
// borders: the texels just outside take each nearest triangle's values extended linearly, so
// bilinear filtering at a border point reads the display's value there, the same value the island
// across the seam reads. Dilate fills a wider gutter, so mipmaps read light instead of black.
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
  uint64_t extended = 0;    // border texels Extend filled
  uint64_t dilated = 0;     // gutter texels Dilate filled
};

class UvRaster {
 public:
  UvRaster(uint32_t width, uint32_t height);

  // Draws one triangle; texels outside [0, 1)^2 are clipped.
  void Draw(const std::array<Uv, 3>& uv, const std::array<Rgb, 3>& value);

  // Fills every empty texel whose centre lies within `reach` texels (Chebyshev distance: the
  // larger of the two axes') of a drawn triangle with that nearest triangle's corner values
  // extended linearly to the centre (each channel at least 0). Reach 1 fills every texel bilinear
  // filtering reads at a point of a drawn triangle.
  void Extend(double reach);

  // Where a 3D edge lies on two islands (a seam), each side's samples along it: the UV of a point
  // and the light the display has there. Fit moves the Extend texels (never the drawn ones) so
  // bilinear filtering at every sample reads its value: `passes` of Gauss-Seidel over the samples,
  // least change to the texels of each, channels kept at least 0.
  struct Sample {
    Uv uv;
    Rgb value;
  };
  void Fit(const std::vector<Sample>& samples, int passes);

  // `texels` passes: each fills every empty texel beside (8-neighbours) a filled one with the mean
  // of those neighbours.
  void Dilate(int texels);

  const Image& image() const { return image_; }
  bool Covered(uint32_t x, uint32_t y) const { return state_[Index(x, y)] != kEmpty; }
  const UvRasterStats& stats() const { return stats_; }

 private:
  enum : uint8_t { kEmpty = 0, kDrawn = 1, kExtended = 2, kDilated = 3 };
  struct Drawn {  // a drawn triangle: corners in texels, counter-clockwise, and their values
    std::array<std::array<double, 2>, 3> at;
    std::array<Rgb, 3> value;
  };
  size_t Index(uint32_t x, uint32_t y) const { return size_t{y} * image_.width + x; }

  Image image_;
  std::vector<uint8_t> state_;
  std::vector<Drawn> drawn_;
  UvRasterStats stats_;
};

}  // namespace radfarm
