// Groups faces into smooth surfaces, the units of vertex averaging. Two faces join when they share
// a stretch of edge (positions within tol; a T-junction where one face's edge covers part of the
// other's counts), have the same material and object (InputFace::object) and normals within
// kSurfaceAngleDegrees; surfaces are the connected groups. A gently non-planar wall split into
// triangles stays one surface, while a floor-wall corner, a material boundary or the seam between
// two of the user's objects separates two (each object is given back on its own: lit.glb).
#pragma once

#include <cstdint>
#include <vector>

#include "mesh/clean_faces.h"

namespace radfarm {

inline constexpr double kSurfaceAngleDegrees = 1.0;

struct SurfaceGroups {
  std::vector<uint32_t> surface;  // per face; ids 0..count-1 in order of each surface's first face
  uint32_t count = 0;
};

SurfaceGroups GroupSurfaces(const std::vector<CleanFace>& faces, double tol);

}  // namespace radfarm
