// A camera read from a scene file (glTF cameras; OBJ has none), in scene coordinates.
#pragma once

#include <string>

#include "core/vec3.h"

namespace radfarm {

struct InputCamera {
  std::string name;       // the camera's node name, as `--camera NAME` matches it
  std::string data_name;  // the glTF camera object's own name (matches too)
  Vec3 eye;
  Vec3 target;  // eye + the view direction
  Vec3 up;
  double fov_degrees = 40;  // vertical
  double aspect_ratio = 0;  // width / height as the file gives it; 0: not given
};

}  // namespace radfarm
