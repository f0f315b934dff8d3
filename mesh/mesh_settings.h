#pragma once

namespace radfarm {

struct MeshSettings {
  // Largest quad patch edge, in scene units; a triangle's longest edge may be sqrt(2) times it,
  // a grid cell's diagonal (mesh/polygon_split.h). 0 picks one automatically from the scene's size.
  double patch_size = 0;
};

}  // namespace radfarm
