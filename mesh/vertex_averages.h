// Per-patch values carried to the display vertices: each vertex gets the area-weighted average of
// the patches of its surface that touch it (as a corner, or with the vertex on an edge: a
// T-vertex). Values never mix across surfaces, so creases stay sharp. Refinement's gradient test
// and the display both read vertex values so.
#pragma once

#include <vector>

#include "core/patch_scene.h"
#include "core/rgb.h"
#include "mesh/display_topology.h"

namespace radfarm {

// Per display vertex, the area-weighted average of `per_patch` over its patches (0 where none).
std::vector<Rgb> VertexAverages(const DisplayTopology& topology, const PatchScene& scene,
                                const std::vector<Rgb>& per_patch);

// VertexAverages with the vertices on a surface's border extrapolated from the inside
// (mesh/border_extrapolation.h): the solution as Gouraud shading between patch means shows it.
std::vector<Rgb> SmoothVertexValues(const DisplayTopology& topology, const PatchScene& scene,
                                    const std::vector<Rgb>& per_patch);

}  // namespace radfarm
