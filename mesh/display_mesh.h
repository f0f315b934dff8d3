// DisplayMesh: triangles with per-vertex radiance, ready to rasterise or write as PLY. Vertices are
// duplicated per surface, so radiance is never averaged across a crease.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/rgb.h"
#include "core/vec3.h"

namespace radfarm {

struct DisplayMesh {
  std::vector<Vec3> positions;
  std::vector<Rgb> radiance;  // per vertex, MTL Ke units
  std::vector<std::array<uint32_t, 3>> triangles;
  std::vector<uint32_t> triangle_patch;  // patch id of each triangle
};

}  // namespace radfarm
