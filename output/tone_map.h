// From linear radiance to 8-bit sRGB: an exposure in stops, the sRGB transfer curve, and clamped
// quantisation. The image writer and the PLY writer share it so their colours agree.
//
// Exposure: the linear values are multiplied by 2^stops, where
//   stops = camera.exposure                          when !camera.auto_exposure
//   stops = AutoExposureStops(image) + camera.exposure  when camera.auto_exposure
// so with auto exposure camera.exposure acts as compensation (0 = as metered).
// Auto exposure maps the 99th-percentile luminance of the non-black pixels to 1.0 (white): robust
// against a few very bright emitter pixels, which are allowed to clip, while the brightest lit
// surfaces land just at white. An all-black image gets 0 stops.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/rgb.h"
#include "output/camera.h"
#include "output/image.h"

namespace radfarm {

inline constexpr double kAutoExposurePercentile = 0.99;

// Rec. 709 / sRGB luminance of linear RGB.
double Luminance(const Rgb& linear);

// The real piecewise sRGB encoding (IEC 61966-2-1) of a linear value in [0, 1]; input outside
// [0, 1] (or NaN) is clamped first.
double SrgbEncode(double linear);
// Inverse of SrgbEncode, for tests and readers.
double SrgbDecode(double encoded);

// Rounds a value in [0, 1] to 0..255, clamping anything outside (NaN gives 0).
uint8_t QuantizeUnit(double value);

double AutoExposureStops(const Image& linear);
double ExposureStops(const Image& linear, const Camera& camera);
// `camera` with auto_exposure off and exposure set to ExposureStops(linear, camera): hand it to
// several writers to make them use one and the same exposure.
Camera WithResolvedExposure(const Image& linear, const Camera& camera);

// Exposure scale (2^stops) applied, then sRGB-encoded and quantised.
std::array<uint8_t, 3> ToneMapPixel(const Rgb& linear, double scale);
// Interleaved 8-bit RGB, row-major, top row first.
std::vector<uint8_t> ToneMapImage(const Image& linear, const Camera& camera);

}  // namespace radfarm
