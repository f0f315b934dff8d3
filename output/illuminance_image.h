// The false-colour picture of an illuminance plane: the grid seen from above (+x to the right, +z
// down), one square of colour per point, each level of the plane (a storey's floor, say) a panel of
// its own from the lowest, left to right; below them a colour bar from 0 to the scale's top with
// its values in lux (output/pixel_font.h). Grid cells without a point are light grey.
#pragma once

#include <array>
#include <string>

#include "base/result.h"
#include "output/illuminance_report.h"
#include "output/pixel_font.h"

namespace radfarm {

// The top of the colour scale: the least 1, 2, 2.5 or 5 times a power of ten at or above `max`
// (1 when `max` is not above 0).
double ColourScaleTop(double max);
// The colour of `lux` on a scale from 0 to `top`: dark blue through cyan, green and yellow to red.
std::array<uint8_t, 3> FalseColour(double lux, double top);
// A tick's label: the value with at most three significant digits, no exponent below 10^7.
std::string TickLabel(double value);

Rgb8Image IlluminanceImage(const PlaneIlluminance& plane);

// Written atomically (base/atomic_file.h); errors name `path`.
Status WriteIlluminancePng(const std::string& path, const PlaneIlluminance& plane);

}  // namespace radfarm
