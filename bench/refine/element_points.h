// Points of equal share spread over an element: where the report samples a reference over a run's
// element (solution_error.cc) and the direct light over a reference patch (reference_image.cc).
#pragma once

#include <vector>

#include "core/patch_scene.h"
#include "mesh/locate_patches.h"

namespace radfarm::bench {

inline constexpr int kElementPointSections = 4;
inline constexpr int kPointsPerElement = kElementPointSections * kElementPointSections;

// Appends kPointsPerElement points of `p`: the centres of a 4 x 4 grid of a quad (bilinear), the
// centroids of the 16 triangles of a triangle cut into 4 sections per edge.
void AppendElementPoints(const Patch& p, std::vector<SurfacePoint>* out);

}  // namespace radfarm::bench
