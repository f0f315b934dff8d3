// The error measures of every table: RMS relative patch error against a reference solution.
//
// sqrt(mean over patches of ((B - Bref) / Bref)^2), B the channel sum of a patch's radiosity, not
// area-weighted: every patch counts once, as every patch is one tile of the image. It is averaged
// over two sets of patches, both fixed by the reference:
//   all: every patch with Bref > 0 (patches with Bref == 0 have no relative error);
//   lit: those with Bref >= kDarkFraction * the median Bref. Both scenes' lights hang a millimetre
//        below the ceiling, and the ceiling patches behind them see light only through that gap:
//        they are about 1000x darker than their neighbours, invisible from the room, and their
//        relative error is that of a handful of rays, large enough to decide the first measure.
#pragma once

#include <cstdint>
#include <vector>

#include "core/rgb.h"

namespace radfarm::bench {

inline constexpr double kDarkFraction = 0.01;

struct ErrorPatches {
  std::vector<uint32_t> all;  // Bref > 0
  std::vector<uint32_t> lit;  // Bref >= kDarkFraction * median Bref
};

ErrorPatches ClassifyPatches(const std::vector<Rgb>& reference);

// The RMS relative error over `patches` (0 when empty).
double RmsRelativeError(const std::vector<Rgb>& radiosity, const std::vector<Rgb>& reference,
                        const std::vector<uint32_t>& patches);

}  // namespace radfarm::bench
