// The sky: light from infinitely far away in every direction above the horizon, in physical units.
// A ray that leaves the scene upward takes the sky's luminance in its direction; below the horizon
// there is no ground (the sky sends nothing from there).
//
// Kinds: a uniform sky (the same luminance everywhere, the closed forms' case), the CIE standard
// overcast sky L(theta) = Lz (1 + 2 cos theta) / 3, and the CIE standard clear sky (ISO 15469 type
// 12, the CIE 1973 clear sky): L(theta, gamma) = Lz f(gamma) phi(theta) / (f(Zs) phi(0)) with
// phi(t) = 1 - exp(-0.32 / cos t), f(g) = 0.91 + 10 exp(-3 g) + 0.45 cos^2 g, theta the zenith
// angle, gamma the angle to the sun and Zs the sun's zenith angle. The clear sky's sun itself is a
// punctual sun (core/punctual_light.h, ClearSkySun), not part of the dome.
//
// Units: luminance in cd/m^2, which is the solver's radiance (MTL Ke units: an irradiance of E lux
// is E / pi there, and a uniform sky of L cd/m^2 gives an open floor E = pi L lux). Up is +Y.
#pragma once

#include <cstdint>
#include <string>

#include "core/rgb.h"
#include "core/vec3.h"

namespace radfarm {

enum class SkyKind : uint8_t { kNone = 0, kUniform = 1, kCieOvercast = 2, kCieClear = 3 };

struct Sky {
  SkyKind kind = SkyKind::kNone;
  double zenith = 0;  // luminance at the zenith, cd/m^2, >= 0 (a uniform sky's everywhere)
  Vec3 sun{0, 1, 0};  // unit, toward the sun; read by the clear sky only
  bool present() const { return kind != SkyKind::kNone && zenith > 0; }
  bool operator==(const Sky&) const = default;
};

// The luminance the sky sends along -w, seen looking toward unit direction w: 0 below the horizon
// (w.y <= 0) and for no sky.
double SkyLuminance(const Sky& sky, const Vec3& w);
inline Rgb SkyRadiance(const Sky& sky, const Vec3& w) {
  const double l = SkyLuminance(sky, w);
  return {l, l, l};
}

// The illuminance the whole sky gives an unobstructed horizontal plane, in lux: pi Lz (uniform),
// 7 pi Lz / 9 (overcast), and for a clear sky a numerical integral of its dome.
double SkyHorizontalIlluminance(const Sky& sky);

// What is wrong with a sky, or "" if nothing: a kind out of range, a zenith luminance not finite
// and >= 0, a clear sky whose sun is not a finite unit vector. Shared by the readers and decoders.
std::string SkyProblem(const Sky& sky);

}  // namespace radfarm
