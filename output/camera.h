// Camera and image settings of a job, plus the automatic camera that frames a bare OBJ.
#pragma once

#include <cstdint>

#include "core/vec3.h"

namespace radfarm {

struct Camera {
  bool automatic = true;  // when true, eye/target/up/fov are derived from the scene's bounds
  Vec3 eye{0, 0, 1};
  Vec3 target{0, 0, 0};
  Vec3 up{0, 1, 0};
  double fov_degrees = 40;  // vertical field of view
  uint32_t width = 512;
  uint32_t height = 512;
  double exposure = 0;  // stops; 0 picks an exposure from the image (see tone_map.h)
  bool auto_exposure = true;
  uint32_t samples_per_pixel = 4;  // antialiasing: a stratified n x n grid with n*n >= this
};

// Looks at the centre of `bounds` along -z from far enough that the whole box fits the view.
Camera AutoCamera(const Bounds3& bounds, const Camera& base);

}  // namespace radfarm
