// How the direct light varies across each patch, for gathering rays that meet it near
// (core/point_gather.h's PatchCornerOffsets).
#pragma once

#include <cstdint>
#include <vector>

#include "core/patch_scene.h"
#include "core/point_gather.h"
#include "core/rgb.h"
#include "mesh/display_topology.h"

namespace radfarm {

// Per patch corner, the direct light it reflects there (rho times `irradiance` at the corner's
// display vertex, whose point is point_of[vertex]) less the patch's mean (rho times
// patch_direct[patch]), with the offsets' own mean over the patch taken off so that they shape the
// light but keep the solution's mean. `scene` must outlive the result.
PatchCornerOffsets CornerDirectOffsets(const DisplayTopology& topology, const PatchScene& scene,
                                       const std::vector<Rgb>& irradiance,
                                       const std::vector<uint32_t>& point_of,
                                       const std::vector<Rgb>& patch_direct);

}  // namespace radfarm
