// What the Gouraud image shows of each patch on average: the area-weighted mean of the radiance
// interpolated linearly over the patch's display triangles (PatchMesh::SetSolution moves vertices
// so that it matches the patch's mean light).
#pragma once

#include <cstddef>
#include <vector>

#include "core/rgb.h"
#include "mesh/display_mesh.h"

namespace radfarm {

// Per patch (0 .. patches - 1), the mean over its triangles of display.radiance interpolated
// linearly; zero for a patch with no triangle of positive area.
std::vector<Rgb> GouraudPatchMeans(const DisplayMesh& display, size_t patches);

}  // namespace radfarm
