#include "output/view_transform.h"

#include <cmath>
#include <numbers>

namespace radfarm {

ViewTransform MakeViewTransform(const Camera& camera) {
  ViewTransform view;
  view.eye = camera.eye;
  Vec3 forward = camera.target - camera.eye;
  if (!(Length(forward) > 0) || !IsFinite(forward)) forward = {0, 0, 1};
  view.forward = Normalize(forward);

  Vec3 right = Cross(view.forward, camera.up);
  // An up vector parallel to the view direction (or zero) leaves no horizon: pick any frame.
  if (!(Length(right) > 1e-12) || !IsFinite(right)) {
    Vec3 unused;
    OrthonormalBasis(view.forward, &right, &unused);
  }
  view.right = Normalize(right);
  view.up = Cross(view.right, view.forward);

  double fov = camera.fov_degrees;
  if (!(fov > 0 && fov < 180)) fov = Camera{}.fov_degrees;
  view.focal_pixels = 0.5 * camera.height / std::tan(fov * std::numbers::pi / 360);
  view.centre_x = 0.5 * camera.width;
  view.centre_y = 0.5 * camera.height;
  return view;
}

}  // namespace radfarm
