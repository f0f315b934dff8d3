// Splits one element (a patch) into four children at its edge midpoints: a quad into four quads
// around its centre, a triangle into its three corner triangles and the middle one. Children keep
// the parent's winding, so their normals are the parent's; a shared edge's midpoint is computed as
// (a + b) / 2 from either side, so neighbours split alike meet exactly.
#pragma once

#include <array>

#include "core/patch_scene.h"
#include "mesh/polygon_split.h"

namespace radfarm {

std::array<PieceCorners, 4> SplitElement(const Patch& element);

// The longest edge of a patch.
double LongestPatchEdge(const Patch& patch);

}  // namespace radfarm
