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
  // By patch id: drawn only from the front (a side of a two-sided surface, whose other side lies
  // in the same place facing the other way). Other patches are drawn from both sides.
  std::vector<bool> patch_front_only;
};

}  // namespace radfarm
