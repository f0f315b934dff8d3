// The patches as display triangles: one vertex per display vertex (surface and position), each
// patch triangulated through the T-vertices on its edges, so Gouraud shading is continuous within
// a surface.
#pragma once

#include <vector>

#include "core/patch_scene.h"
#include "core/rgb.h"
#include "display/display_mesh.h"
#include "mesh/display_topology.h"

namespace radfarm {

// `radiance` holds one value per display vertex. A quad without T-vertices is split as the Patch
// contract names, (0, 1, 2) and (0, 2, 3); any other ring is ear-clipped in its plane.
DisplayMesh PatchTriangles(const DisplayTopology& topology, const PatchScene& scene,
                           std::vector<Rgb> radiance);

}  // namespace radfarm
