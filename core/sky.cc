#include "core/sky.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace radfarm {
namespace {

constexpr double kPi = std::numbers::pi;

// The CIE clear sky's gradation (phi) and indicatrix (f), ISO 15469 type 12.
double Gradation(double cos_theta) { return 1 - std::exp(-0.32 / cos_theta); }
double Indicatrix(double gamma) {
  const double c = std::cos(gamma);
  return 0.91 + 10 * std::exp(-3 * gamma) + 0.45 * c * c;
}

double AngleBetween(const Vec3& a, const Vec3& b) {
  return std::acos(std::clamp(Dot(a, b), -1.0, 1.0));
}

}  // namespace

double SkyLuminance(const Sky& sky, const Vec3& w) {
  if (!(w.y > 0)) return 0;
  switch (sky.kind) {
    case SkyKind::kNone:
      return 0;
    case SkyKind::kUniform:
      return sky.zenith;
    case SkyKind::kCieOvercast:
      return sky.zenith * (1 + 2 * w.y) / 3;
    case SkyKind::kCieClear: {
      // The sun's zenith angle, kept above the horizon: a sun below it leaves the dome's shape at
      // its sunset limit.
      const double sun_zenith = std::min(AngleBetween(sky.sun, {0, 1, 0}), kPi / 2 - 1e-3);
      const double norm = Indicatrix(sun_zenith) * Gradation(1.0);
      return sky.zenith * Indicatrix(AngleBetween(w, sky.sun)) * Gradation(w.y) / norm;
    }
  }
  return 0;
}

double SkyHorizontalIlluminance(const Sky& sky) {
  switch (sky.kind) {
    case SkyKind::kNone:
      return 0;
    case SkyKind::kUniform:
      return kPi * sky.zenith;
    case SkyKind::kCieOvercast:
      return 7 * kPi * sky.zenith / 9;
    case SkyKind::kCieClear:
      break;
  }
  // Midpoint rule in (cos^2 theta, phi), where L cos dOmega is L d(cos^2) dphi / 2: fine enough
  // near the sun's bright circumsolar term that the sum holds to better than 0.1 %.
  constexpr int kRings = 400, kSectors = 800;
  double sum = 0;
  for (int i = 0; i < kRings; ++i) {
    const double cos_theta = std::sqrt((i + 0.5) / kRings);
    const double sin_theta = std::sqrt(1 - cos_theta * cos_theta);
    for (int j = 0; j < kSectors; ++j) {
      const double phi = 2 * kPi * (j + 0.5) / kSectors;
      sum += SkyLuminance(sky, {sin_theta * std::cos(phi), cos_theta, sin_theta * std::sin(phi)});
    }
  }
  return sum * kPi / (double(kRings) * kSectors);
}

std::string SkyProblem(const Sky& sky) {
  if (static_cast<uint8_t>(sky.kind) > static_cast<uint8_t>(SkyKind::kCieClear)) {
    return "sky kind out of range";
  }
  if (!std::isfinite(sky.zenith) || !(sky.zenith >= 0)) {
    return "sky zenith luminance must be finite and >= 0";
  }
  if (sky.kind == SkyKind::kCieClear &&
      (!IsFinite(sky.sun) || std::fabs(Length(sky.sun) - 1) > 1e-6)) {
    return "clear sky's sun direction must be a finite unit vector";
  }
  return "";
}

}  // namespace radfarm
