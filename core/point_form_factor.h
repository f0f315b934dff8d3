// The form factor from a differential area at a point to a planar polygon, in closed form
// (Lambert's contour integral): F = 1/(2 pi) sum over edges of the angle the edge subtends times
// the cosine between the receiver's normal and the normal of the plane through the point and the
// edge. The part of the polygon below the receiver's tangent plane is clipped away first, and a
// polygon whose back faces the point contributes nothing. Occlusion is not considered: callers
// multiply by a visibility estimate.
#pragma once

#include <utility>
#include <vector>

#include "core/patch_scene.h"
#include "core/vec3.h"

namespace radfarm {

// Unoccluded form factor from the point `x` with unit normal `n` to `patch` (a triangle or quad).
double PointToPatchFormFactor(const Vec3& x, const Vec3& n, const Patch& patch);

// A planar light made of patches, as the edges of its outline: the contour integral over the
// patches' edges, where the edges two patches share run both ways and cancel, so only these are
// summed, and the pieces of a straight side, end to end, are one edge (a T-vertex's pieces then
// cancel the whole edge they run against; where they cannot be joined they still sum correctly).
struct PlanarOutline {
  std::vector<std::pair<Vec3, Vec3>> edges;  // directed as the patches wind about `normal`
  Vec3 normal;                               // unit, the patches' common normal
  Vec3 point;                                // any point of the plane
};

// The outline of these coplanar patches (same unit normal), or none (no edges) when they are
// not: their normals differ, or a corner is off the first patch's plane by more than `tol`.
PlanarOutline OutlineOf(const std::vector<const Patch*>& patches, double tol);

// Unoccluded form factor from x (unit normal n) to the whole outlined light, where no clipping is
// needed: x in front of its plane and every outline corner strictly above x's tangent plane.
// Elsewhere returns a negative value: the caller sums PointToPatchFormFactor over the patches.
double PointToOutlineFormFactor(const Vec3& x, const Vec3& n, const PlanarOutline& outline);

// The same where the light needs clipping: the outline's edges clipped to x's upper half-space
// (as PointToPatchFormFactor clips a patch), closed along the line where the light's plane meets
// x's tangent plane (the crossings, sorted along it, pair up into the stretches of the light it
// crosses). Zero where x is not in front of the light's plane; negative where there is no outline
// or the crossings do not pair up (a T-vertex's unpaired pieces on the line): the caller sums
// PointToPatchFormFactor over the patches. Equal to that sum up to rounding, at the cost of one
// contour instead of one per patch (tests/core/point_form_factor_test.cc).
double PointToClippedOutlineFormFactor(const Vec3& x, const Vec3& n, const PlanarOutline& outline);

}  // namespace radfarm
