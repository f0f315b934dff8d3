#include "output/tone_map.h"

#include <algorithm>
#include <cmath>

namespace radfarm {

double Luminance(const Rgb& linear) {
  return 0.2126 * linear.r + 0.7152 * linear.g + 0.0722 * linear.b;
}

double SrgbEncode(double linear) {
  if (!(linear > 0)) return 0;  // also NaN
  if (linear >= 1) return 1;
  if (linear <= 0.0031308) return 12.92 * linear;
  return 1.055 * std::pow(linear, 1 / 2.4) - 0.055;
}

double SrgbDecode(double encoded) {
  if (!(encoded > 0)) return 0;
  if (encoded >= 1) return 1;
  if (encoded <= 0.04045) return encoded / 12.92;
  return std::pow((encoded + 0.055) / 1.055, 2.4);
}

uint8_t QuantizeUnit(double value) {
  if (!(value > 0)) return 0;
  if (value >= 1) return 255;
  return static_cast<uint8_t>(std::floor(value * 255 + 0.5));
}

double AutoExposureStops(const Image& linear) {
  std::vector<double> luminances;
  luminances.reserve(linear.pixels.size());
  for (const Rgb& p : linear.pixels) {
    const double y = Luminance(p);
    if (y > 0 && std::isfinite(y)) luminances.push_back(y);
  }
  if (luminances.empty()) return 0;
  // The value at index floor(p * (n - 1)) of the sorted luminances.
  const size_t rank = static_cast<size_t>(kAutoExposurePercentile * (luminances.size() - 1));
  std::nth_element(luminances.begin(), luminances.begin() + rank, luminances.end());
  const double stops = -std::log2(luminances[rank]);
  return std::isfinite(stops) ? stops : 0;
}

double ExposureStops(const Image& linear, const Camera& camera) {
  const double compensation = std::isfinite(camera.exposure) ? camera.exposure : 0;
  return camera.auto_exposure ? AutoExposureStops(linear) + compensation : compensation;
}

Camera WithResolvedExposure(const Image& linear, const Camera& camera) {
  Camera resolved = camera;
  resolved.exposure = ExposureStops(linear, camera);
  resolved.auto_exposure = false;
  return resolved;
}

std::array<uint8_t, 3> ToneMapPixel(const Rgb& linear, double scale) {
  return {QuantizeUnit(SrgbEncode(linear.r * scale)), QuantizeUnit(SrgbEncode(linear.g * scale)),
          QuantizeUnit(SrgbEncode(linear.b * scale))};
}

std::vector<uint8_t> ToneMapImage(const Image& linear, const Camera& camera) {
  const double scale = std::exp2(ExposureStops(linear, camera));
  std::vector<uint8_t> bytes;
  bytes.reserve(linear.pixels.size() * 3);
  for (const Rgb& p : linear.pixels) {
    const std::array<uint8_t, 3> rgb = ToneMapPixel(p, scale);
    bytes.insert(bytes.end(), rgb.begin(), rgb.end());
  }
  return bytes;
}

}  // namespace radfarm
