#pragma once

namespace radfarm {

struct MeshSettings {
  // Largest patch edge, in scene units. 0 picks one automatically from the scene's size.
  double patch_size = 0;
};

}  // namespace radfarm
