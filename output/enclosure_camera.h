// The automatic camera for a closed scene: a room modelled with all its walls is seen from inside,
// not as a box from outside (where the automatic camera of an open scene, AutoCamera, would show
// one wall).
#pragma once

#include <optional>

#include "display/display_mesh.h"
#include "output/camera.h"

namespace radfarm {

// An inside view when one exists, else nothing (the scene is open). Candidate places stand on
// lines across the bounds along +z, +x, -z and -x (y up), at a few heights and sideways places,
// at a few depths each. Rays from a place in 128 directions (a spiral over the sphere, which meets
// no edge or corner of an axis-aligned box exactly) count what they meet: the front of a surface,
// its back (inside a solid block, or behind a wall), or nothing; a few may slip through cracks.
// A place in open space (no backs) from which more than a few rays leave the scene makes the
// scene open, even if another place (a nook behind a block) looks closed. Along each line, the
// first place from the wall behind that almost only meets fronts, with nothing within
// kEyeClearance of the bounds' smallest extent, is that line's eye. Of the eyes, the one that sees
// deepest along its line wins (a fan of 9 rays; an earlier one unless another sees 10% deeper: the
// Cornell box's +z first), looking along the line with a field of view in which the far end of the
// bounds fills 65% of the frame (50-90 degrees vertically).
//
// Cost: an Embree BVH of the triangles, and a few thousand to some 25,000 rays.
std::optional<Camera> InsideCamera(const DisplayMesh& mesh, const Bounds3& bounds,
                                   const Camera& base);

// The eye's least distance to geometry, as a share of the bounds' smallest extent.
inline constexpr double kEyeClearance = 0.08;

}  // namespace radfarm
