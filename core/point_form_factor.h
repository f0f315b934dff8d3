// The form factor from a differential area at a point to a planar polygon, in closed form
// (Lambert's contour integral): F = 1/(2 pi) sum over edges of the angle the edge subtends times
// the cosine between the receiver's normal and the normal of the plane through the point and the
// edge. The part of the polygon below the receiver's tangent plane is clipped away first, and a
// polygon whose back faces the point contributes nothing. Occlusion is not considered: callers
// multiply by a visibility estimate.
#pragma once

#include "core/patch_scene.h"
#include "core/vec3.h"

namespace radfarm {

// Unoccluded form factor from the point `x` with unit normal `n` to `patch` (a triangle or quad).
double PointToPatchFormFactor(const Vec3& x, const Vec3& n, const Patch& patch);

}  // namespace radfarm
