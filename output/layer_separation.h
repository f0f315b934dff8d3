// Where lit.glb puts the vertices of two-sided surfaces. Such a surface is two layers of display
// triangles at the same place facing opposite ways (DisplayMesh::patch_front_only): a room's lit
// inside and its dark outside. A viewer that draws back faces (Blender's Solid view does by
// default) then draws both at the same depth and z-fights. Each front-only layer is moved a hair
// along its own normal, so from either side the layer facing the eye is the nearer one: the
// layers part by 2 * kLayerGap of the scene's size, far below a patch yet above a viewport's depth
// resolution. Other vertices keep their places.
#pragma once

#include <vector>

#include "core/vec3.h"
#include "display/display_mesh.h"

namespace radfarm {

// Each front-only layer's offset, as a fraction of the diagonal of the mesh's bounding box.
inline constexpr double kLayerGap = 1.0 / 4096;

// The mesh's positions, by vertex, with front-only vertices moved kLayerGap of the diagonal along
// the area-weighted normal of their front-only triangles (a vertex whose triangles cancel stays).
std::vector<Vec3> SeparatedLayerPositions(const DisplayMesh& mesh);

}  // namespace radfarm
