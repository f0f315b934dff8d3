// The automatic camera for a closed scene: a room modelled with all its walls is seen from inside,
// not as a box from outside (where the automatic camera of an open scene, AutoCamera, would show
// one wall).
#pragma once

#include <optional>

#include "display/display_mesh.h"
#include "output/camera.h"

namespace radfarm {

// Whether the centre of `bounds` is enclosed by `mesh`: rays from it in 26 directions (the faces,
// edges and corners of a cube) all hit a triangle, and the free span through it along x and z is at
// least a quarter of the scene's extent (the centre is in a room, not inside a solid block at the
// middle). Then the camera stands just inside a wall, at the centre's height, and looks at the
// centre along +z, +x, -z or -x: whichever sees deepest into the room (a fan of 9 rays from each
// eye; +z, the Cornell box's convention, unless another sees 10% deeper), with a field of view in
// which the far end of the scene's bounds fills 65% of the frame (50-90 degrees vertically, y up).
// Otherwise nothing: the scene is open.
//
// Cost: two passes over the triangles, 26 and 36 ray tests each.
std::optional<Camera> InsideCamera(const DisplayMesh& mesh, const Bounds3& bounds,
                                   const Camera& base);

}  // namespace radfarm
