// The last step of the display: each patch's mean light as the display's points measured it, and
// the step that moves the points so that every patch shows that mean (display/gouraud_means.h).
#pragma once

#include <cstdint>
#include <vector>

#include "core/patch_scene.h"
#include "core/rgb.h"
#include "display/display_mesh.h"
#include "display/midpoint_split.h"

namespace radfarm {

// Per patch, the direct light's integral over its area and that area (both times 3 and 2, as the
// sums fall out): the mean is sum / (3 area).
struct PatchDirectSums {
  std::vector<Rgb> sum;
  std::vector<double> area;
};

// Each patch's triangles by the midpoint rule (the mean of its edge midpoints' values, exact for
// quadratics), from `irradiance` per vertex of the split mesh.
PatchDirectSums MidpointRuleSums(const MidpointSplit& split, const std::vector<Rgb>& irradiance,
                                 size_t patches);

// A patch the refinement cut (a triangle with a vertex at or past `first_new`) holds a shadow's
// edge or a steep rise, which three midpoints per triangle miss: its sum is remade from the
// refined triangles, each the mean of its corners.
void RemeasureRefinedPatches(const DisplayMesh& fine, uint32_t first_new,
                             const std::vector<Rgb>& irradiance, PatchDirectSums* sums);

// One step toward each patch's mean light: `rest` (the solution less rho times the patch's direct
// light) plus rho times the measured mean direct light. Emitters show their emission and stay;
// `held` points (gathered) keep their values.
void StepTowardMeanLight(const PatchScene& scene, const std::vector<Rgb>& rest,
                         const PatchDirectSums& sums, const std::vector<bool>& held,
                         DisplayMesh* fine);

}  // namespace radfarm
