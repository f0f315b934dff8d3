// Punctual lights: points, spots and suns (glTF KHR_lights_punctual) and photometric lamps (an IES
// file's candela distribution, core/candela_table.h), lights with no surface. They
// light the patches directly (core/direct_light.h, with a shadow ray each) and their light then
// bounces as the emitters' does; nothing ever hits them.
//
// Units: a point or spot light's intensity is in candela, a sun's in lux, as glTF defines them,
// with the scene in metres; a photometric lamp's candela are its table's times its intensity, a
// colour and scale. The irradiance returned here is in the solver's units, those of
// emitted radiance (MTL Ke, glTF emissive: core/progressive_solver.h), i.e. lux / pi: a floor of
// reflectance rho under a lamp of I cd at d metres then shows the radiance rho I / (pi d^2).
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "core/candela_table.h"
#include "core/rgb.h"
#include "core/vec3.h"

namespace radfarm {

enum class PunctualKind : uint8_t { kPoint = 0, kSpot = 1, kSun = 2, kPhotometric = 3 };

struct PunctualLight {
  PunctualKind kind = PunctualKind::kPoint;
  Vec3 position;     // world space (point, spot); unused for a sun
  Vec3 direction;    // unit, the way the light travels (spot axis, sun rays): the node's -Z;
                     // a photometric lamp's nadir axis (vertical angle 0)
  Rgb intensity;     // linear colour times intensity: candela (point, spot) or lux (sun), >= 0;
                     // a photometric lamp's colour and multiplier of its table's candela
  double range = 0;  // metres; 0: unlimited (point, spot)
  // Spot cone half-angles in radians, 0 <= inner < outer <= pi / 2 (glTF's defaults 0, pi / 4).
  double inner_cone = 0;
  double outer_cone = 0.7853981633974483;
  // Photometric lamps only. `reference`: unit, perpendicular to `direction`, where the horizontal
  // angle is 0; 90 lies along Cross(reference, direction) (LM-63 type C, seen from above a lamp
  // aimed down: counter-clockwise). `table` is shared by copies of the light and never changes;
  // `table_lumens` is its TableLumens, computed once by MakePhotometricLight.
  Vec3 reference;
  std::shared_ptr<const CandelaTable> table;
  double table_lumens = 0;
};

// A photometric lamp at `position`, aimed along `nadir` (unit) with horizontal angle 0 toward
// `reference` (unit, perpendicular to it), emitting `scale` times the table's candela.
PunctualLight MakePhotometricLight(const Vec3& position, const Vec3& nadir, const Vec3& reference,
                                   const Rgb& scale, CandelaTable table);

// The candela a photometric lamp sends along the unit direction `w` (away from the lamp), without
// its intensity's colour and scale.
double PhotometricCandela(const PunctualLight& light, const Vec3& w);

// A light's luminous flux in the solver's units (lumens / pi): 4 I for a point, a spot's whole
// cone at full intensity (an upper bound), a photometric lamp's table lumens / pi; 0 for a sun,
// whose power has no bound.
double PunctualPower(const PunctualLight& light);

// What is wrong with a light, or "" if nothing: a non-finite or non-unit direction, a non-finite
// position, an intensity not finite and >= 0, a range not finite and >= 0, a kind out of range,
// spot cones outside 0 <= inner <= outer <= pi / 2, or a photometric lamp without a table, with
// a table that has a problem, or a reference not unit and perpendicular to its direction. Shared
// by the readers and the decoders.
std::string PunctualLightProblem(const PunctualLight& light);

// The spot's angular falloff as glTF's KHR_lights_punctual recommends: 1 inside the inner cone, 0
// outside the outer one, and between them the square of a ramp that is linear in the cosine.
// `cos_angle` is the cosine between the spot's axis and the direction to the lit point.
double SpotFalloff(const PunctualLight& light, double cos_angle);

// The irradiance at x (unit normal n) from one light with nothing in the way, in the solver's
// units (see above): I cos(theta) / d^2 times the cone and range windows (a photometric lamp's I
// from its table toward x), or a sun's lux times cos(theta), each divided by pi. Zero for points
// behind the surface.
Rgb UnshadowedIrradiance(const PunctualLight& light, const Vec3& x, const Vec3& n);

// Where a shadow ray from x toward the light ends: the light's position, or for a sun a point
// `reach` metres toward it (reach beyond the scene's extent: nothing past it can cast a shadow).
Vec3 ShadowRayTarget(const PunctualLight& light, const Vec3& x, double reach);

}  // namespace radfarm
