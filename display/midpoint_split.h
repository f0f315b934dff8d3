// A display mesh with every triangle cut into four at its edge midpoints, so the display can show
// light at twice the solution's resolution (the display, display/display_stage.h, computes the
// direct light at each midpoint). A midpoint is shared by the triangles on both sides of its edge,
// so a conforming display stays conforming: no crack opens where a coarse edge was.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "display/display_mesh.h"

namespace radfarm {

struct MidpointSplit {
  // Positions: the coarse mesh's, then one per edge; radiance: the coarse vertices' values, then
  // the mean of each edge's ends. Coarse triangle t becomes triangles 4t .. 4t + 3 of its patch:
  // the three corner triangles (at corners 0, 1, 2), then the middle one.
  DisplayMesh mesh;
  // Per midpoint (mesh vertex coarse_vertices + k), the coarse vertices of its edge.
  std::vector<std::array<uint32_t, 2>> edge_ends;
  // Per coarse triangle, the vertex ids of the midpoints of its edges (v0 v1, v1 v2, v2 v0).
  std::vector<std::array<uint32_t, 3>> triangle_midpoints;
  uint32_t coarse_vertices = 0;
};

// Midpoints are numbered in the order their edges first appear in the triangle list, so the split
// is a pure function of the coarse mesh.
MidpointSplit SplitAtMidpoints(const DisplayMesh& coarse);

}  // namespace radfarm
