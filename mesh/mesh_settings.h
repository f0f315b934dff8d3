#pragma once

#include <cstdint>

namespace radfarm {

struct MeshSettings {
  // Largest quad patch edge, in scene units; a triangle's longest edge may be sqrt(2) times it,
  // a grid cell's diagonal (mesh/polygon_split.h). 0 picks one automatically from the scene's size.
  double patch_size = 0;
  // Refuse a mesh whose solve would need more memory than this, in bytes (memory_estimate.h);
  // 0: this machine's physical memory. Not a job file key: it belongs to the machine that solves.
  uint64_t max_memory = 0;
  // Threads that mesh (the probes, the narrow-space search, the T-vertex search); 0: one per
  // core. The mesh is the same bits for any count. Not a job file key either.
  unsigned threads = 0;
};

}  // namespace radfarm
