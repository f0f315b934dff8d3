// Punctual lights (glTF KHR_lights_punctual): points, spots and suns, lights with no surface. They
// light the patches directly (core/direct_light.h, with a shadow ray each) and their light then
// bounces as the emitters' does; nothing ever hits them.
//
// Units: a point or spot light's intensity is in candela, a sun's in lux, as glTF defines them,
// with the scene in metres. The irradiance returned here is in the solver's units, those of
// emitted radiance (MTL Ke, glTF emissive: core/progressive_solver.h), i.e. lux / pi: a floor of
// reflectance rho under a lamp of I cd at d metres then shows the radiance rho I / (pi d^2).
#pragma once

#include <cstdint>
#include <string>

#include "core/rgb.h"
#include "core/vec3.h"

namespace radfarm {

enum class PunctualKind : uint8_t { kPoint = 0, kSpot = 1, kSun = 2 };

struct PunctualLight {
  PunctualKind kind = PunctualKind::kPoint;
  Vec3 position;     // world space (point, spot); unused for a sun
  Vec3 direction;    // unit, the way the light travels (spot axis, sun rays): the node's -Z
  Rgb intensity;     // linear colour times intensity: candela (point, spot) or lux (sun), >= 0
  double range = 0;  // metres; 0: unlimited (point, spot)
  // Spot cone half-angles in radians, 0 <= inner < outer <= pi / 2 (glTF's defaults 0, pi / 4).
  double inner_cone = 0;
  double outer_cone = 0.7853981633974483;
};

// What is wrong with a light, or "" if nothing: a non-finite or non-unit direction, a non-finite
// position, an intensity not finite and >= 0, a range not finite and >= 0, a kind out of range, or
// spot cones outside 0 <= inner <= outer <= pi / 2. Shared by the glTF reader and the decoders.
std::string PunctualLightProblem(const PunctualLight& light);

// The spot's angular falloff as glTF's KHR_lights_punctual recommends: 1 inside the inner cone, 0
// outside the outer one, and between them the square of a ramp that is linear in the cosine.
// `cos_angle` is the cosine between the spot's axis and the direction to the lit point.
double SpotFalloff(const PunctualLight& light, double cos_angle);

// The irradiance at x (unit normal n) from one light with nothing in the way, in the solver's
// units (see above): I cos(theta) / d^2 times the cone and range windows, or a sun's lux times
// cos(theta), each divided by pi. Zero for points behind the surface.
Rgb UnshadowedIrradiance(const PunctualLight& light, const Vec3& x, const Vec3& n);

// Where a shadow ray from x toward the light ends: the light's position, or for a sun a point
// `reach` metres toward it (reach beyond the scene's extent: nothing past it can cast a shadow).
Vec3 ShadowRayTarget(const PunctualLight& light, const Vec3& x, double reach);

}  // namespace radfarm
