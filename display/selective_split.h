// A display mesh with chosen triangles cut into four at their edge midpoints, where the light bends
// faster than the display's spacing (display/display_stage.h: the ceiling just outside a hanging
// lamp's outline, whose light rises within a few centimetres). A triangle beside a cut one that has
// one cut edge is cut in two through that edge's midpoint; one with two or three is cut into four
// as well. So the display stays conforming: no crack opens along a cut edge.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "display/display_mesh.h"

namespace radfarm {

struct SelectiveSplit {
  // Positions: the mesh's, then one per cut edge; radiance: the mesh's, then the mean of each cut
  // edge's ends. Triangles keep their patch.
  DisplayMesh mesh;
  // Per new vertex (mesh vertex first_new + k), the two vertices of its edge.
  std::vector<std::array<uint32_t, 2>> edge_ends;
  uint32_t first_new = 0;
};

// Cuts the triangles marked in `marked` (one flag per triangle) and what conformity needs.
// Midpoints are numbered in the order their edges first appear in the triangle list: a pure
// function of the mesh and the marks.
SelectiveSplit SplitMarked(const DisplayMesh& mesh, std::vector<bool> marked);

}  // namespace radfarm
