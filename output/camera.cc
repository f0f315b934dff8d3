#include "output/camera.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace radfarm {

Camera AutoCamera(const Bounds3& bounds, const Camera& base) {
  Camera camera = base;
  camera.automatic = false;
  // An empty or non-finite box (no geometry, bad input) still yields a usable camera: a unit
  // sphere.
  Vec3 centre = bounds.Empty() ? Vec3{} : bounds.Centre();
  double radius = 0.5 * bounds.Diagonal();
  if (!IsFinite(centre)) centre = Vec3{};
  if (!(radius > 0) || !std::isfinite(radius)) radius = 1;
  if (!(camera.fov_degrees > 0 && camera.fov_degrees < 180))
    camera.fov_degrees = Camera{}.fov_degrees;

  // Fit the bounding sphere to the narrower of the two fields of view: a sphere of radius r seen
  // from distance d subtends a half-angle asin(r / d).
  const double half_vertical = camera.fov_degrees * std::numbers::pi / 360;
  const double aspect = (camera.width > 0 && camera.height > 0)
                            ? static_cast<double>(camera.width) / camera.height
                            : 1.0;
  const double half_horizontal = std::atan(aspect * std::tan(half_vertical));
  const double distance = radius / std::sin(std::min(half_vertical, half_horizontal));

  // From the -z side looking toward +z, up +y: the convention of the Cornell box data, whose open
  // front faces -z.
  camera.target = centre;
  camera.eye = centre - Vec3{0, 0, distance};
  camera.up = Vec3{0, 1, 0};
  return camera;
}

}  // namespace radfarm
