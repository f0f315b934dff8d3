#include "core/punctual_light.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <utility>

namespace radfarm {

std::string PunctualLightProblem(const PunctualLight& light) {
  if (static_cast<uint8_t>(light.kind) > static_cast<uint8_t>(PunctualKind::kPhotometric)) {
    return "kind " + std::to_string(static_cast<int>(light.kind)) +
           " is not point, spot, sun or photometric";
  }
  if (!IsFinite(light.position)) return "position is not finite";
  const double length = Length(light.direction);
  if (!IsFinite(light.direction) || !(length > 0.999 && length < 1.001)) {
    return "direction is not a unit vector";
  }
  if (!light.intensity.IsFinite() || light.intensity.Min() < 0) {
    return "intensity is negative or not finite";
  }
  if (!std::isfinite(light.range) || light.range < 0) return "range is negative or not finite";
  if (!(light.inner_cone >= 0 && light.inner_cone <= light.outer_cone &&
        light.outer_cone <= std::numbers::pi / 2)) {
    return "cone angles must satisfy 0 <= innerConeAngle <= outerConeAngle <= pi/2";
  }
  if (light.kind != PunctualKind::kPhotometric) return "";
  if (light.table == nullptr) return "a photometric light has no candela table";
  if (std::string problem = CandelaTableProblem(*light.table); !problem.empty()) return problem;
  const double ref = Length(light.reference);
  if (!IsFinite(light.reference) || !(ref > 0.999 && ref < 1.001) ||
      std::abs(Dot(light.reference, light.direction)) > 1e-3) {
    return "the reference direction is not a unit vector perpendicular to the direction";
  }
  return "";
}

PunctualLight MakePhotometricLight(const Vec3& position, const Vec3& nadir, const Vec3& reference,
                                   const Rgb& scale, CandelaTable table) {
  PunctualLight light;
  light.kind = PunctualKind::kPhotometric;
  light.position = position;
  light.direction = nadir;
  light.reference = reference;
  light.intensity = scale;
  light.table_lumens = TableLumens(table);
  light.table = std::make_shared<const CandelaTable>(std::move(table));
  return light;
}

double PhotometricCandela(const PunctualLight& light, const Vec3& w) {
  constexpr double kDegrees = 180 / std::numbers::pi;
  const double theta = std::acos(std::clamp(Dot(w, light.direction), -1.0, 1.0)) * kDegrees;
  const Vec3 ninety = Cross(light.reference, light.direction);
  const double phi = std::atan2(Dot(w, ninety), Dot(w, light.reference)) * kDegrees;
  return CandelaAt(*light.table, theta, phi);
}

double PunctualPower(const PunctualLight& light) {
  switch (light.kind) {
    case PunctualKind::kPoint:
      return 4 * light.intensity.Sum();
    case PunctualKind::kSpot:
      return 2 * (1 - std::cos(light.outer_cone)) * light.intensity.Sum();
    case PunctualKind::kPhotometric:
      return light.table_lumens / std::numbers::pi * light.intensity.Sum();
    case PunctualKind::kSun:
      break;
  }
  return 0;
}

double SpotFalloff(const PunctualLight& light, double cos_angle) {
  const double cos_outer = std::cos(light.outer_cone);
  // glTF's recommended form; the 0.001 keeps equal cones (a hard edge) finite.
  const double scale = 1.0 / std::max(0.001, std::cos(light.inner_cone) - cos_outer);
  const double ramp = std::clamp((cos_angle - cos_outer) * scale, 0.0, 1.0);
  return ramp * ramp;
}

Rgb UnshadowedIrradiance(const PunctualLight& light, const Vec3& x, const Vec3& n) {
  if (light.kind == PunctualKind::kSun) {
    const double cos_theta = -Dot(n, light.direction);
    if (!(cos_theta > 0)) return {};
    return light.intensity * (cos_theta / std::numbers::pi);
  }
  const Vec3 to_light = light.position - x;
  const double d2 = Dot(to_light, to_light);
  if (!(d2 > 0)) return {};
  const double d = std::sqrt(d2);
  const double cos_theta = Dot(n, to_light) / d;
  if (!(cos_theta > 0)) return {};
  double window = 1;
  if (light.kind == PunctualKind::kSpot) {
    window = SpotFalloff(light, -Dot(light.direction, to_light) / d);
    if (!(window > 0)) return {};
  }
  if (light.kind == PunctualKind::kPhotometric) {
    window = PhotometricCandela(light, to_light * (-1 / d));
    if (!(window > 0)) return {};
  }
  if (light.range > 0) {
    // glTF's recommended range window: smooth to zero at `range`, about 1 well inside it.
    const double q = d2 / (light.range * light.range);
    window *= std::clamp(1 - q * q, 0.0, 1.0);
    if (!(window > 0)) return {};
  }
  return light.intensity * (window * cos_theta / (d2 * std::numbers::pi));
}

Vec3 ShadowRayTarget(const PunctualLight& light, const Vec3& x, double reach) {
  if (light.kind == PunctualKind::kSun) return x - light.direction * reach;
  return light.position;
}

}  // namespace radfarm
