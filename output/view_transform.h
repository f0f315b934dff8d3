// The pinhole camera as the rasteriser uses it: an orthonormal camera frame and the projection of
// camera-space points to continuous pixel coordinates.
#pragma once

#include <cstdint>

#include "core/vec3.h"
#include "output/camera.h"

namespace radfarm {

// Camera space: x to the right of the image, y up, z along the view direction (depth, > 0 in
// front). Pixel space: x in [0, width) to the right, y in [0, height) downward; pixel (i, j) covers
// [i, i + 1) x [j, j + 1), so its centre is at (i + 0.5, j + 0.5).
struct ViewTransform {
  Vec3 eye;
  Vec3 right, up, forward;  // orthonormal, right-handed: right = forward x up
  double focal_pixels = 1;  // pixel distance per unit of x / z
  double centre_x = 0, centre_y = 0;

  Vec3 ToCamera(const Vec3& p) const {
    const Vec3 d = p - eye;
    return {Dot(d, right), Dot(d, up), Dot(d, forward)};
  }
  // Only for camera-space points with z > 0.
  double PixelX(const Vec3& c) const { return centre_x + focal_pixels * c.x / c.z; }
  double PixelY(const Vec3& c) const { return centre_y - focal_pixels * c.y / c.z; }
};

// Uses camera.eye/target/up/fov_degrees as given (resolve `automatic` first). Degenerate input (eye
// on target, up along the view) falls back to a valid frame rather than producing NaNs.
ViewTransform MakeViewTransform(const Camera& camera);

}  // namespace radfarm
