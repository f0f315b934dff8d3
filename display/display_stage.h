// The display: a stage after the solve that turns a solution (one value per patch) into the
// triangles the image, the PLY, lit.glb and the lightmaps are drawn from. Its inputs and output
// are plain data; it is a pure function of them and of DisplaySettings' seed, whatever the
// threads.
//
// AveragedDisplay shows each display vertex the area-weighted average of its patches (borders
// extrapolated from the inside: mesh/vertex_averages.h), no ray cast.
//
// ShadeDisplay is finer than the solution and shows the direct light where it is computed. Every
// display triangle is cut into four at its edge midpoints (display/midpoint_split.h), and every
// display point, vertex or midpoint (display/display_points.h), shows rho times DirectLight at the
// point itself (core/direct_light.h) plus the rest of the solution (radiosity less rho times the
// patch's direct light: emission and bounced light, which is smooth) averaged over the patches
// around it, linearly between a midpoint's two ends. Averages put a vertex at the mean of its
// patches: where the direct light bends (the fall-off near a light, a penumbra) that is not its
// value there, and the Gouraud image would show every patch's outline; the direct light at the
// point is exact outside shadows. Near another surface (within kGatherBand patch sizes: corners,
// the ceiling beside a hanging lamp, the floor around a block) the rest is not smooth across a
// patch: such points gather it themselves (core/point_gather.h) and keep their values. Where the
// light bends the triangles are cut further (display/light_bends.h). Then one step
// (display/gouraud_means.h) moves every point by its patches' shortfall of Gouraud mean against
// mean light (the rest as solved plus rho times the direct light's mean over the patch by the
// midpoint rule, exact for quadratics): point values interpolated linearly run below a concave
// light between points. Under a ray allowance the rays are fitted as display/display_ray_plan.h
// says. Its ray work is planned and applied as the rounds' (display/display_plan.h), so that it
// can be traced anywhere; ShadeDisplay traces it here, on DisplaySettings' threads.
#pragma once

#include <vector>

#include "core/patch_scene.h"
#include "core/rgb.h"
#include "display/display_mesh.h"
#include "display/display_settings.h"
#include "mesh/display_topology.h"

namespace radfarm {

// The solved patches the display shows. All must outlive the call.
struct DisplayInput {
  const DisplayTopology& topology;
  const PatchScene& scene;
  // The target patch size of the mesh (PatchMesh::patch_size): kGatherBand's unit.
  double patch_size = 0;
  const std::vector<Rgb>& radiosity;
  // The direct light the solve started from (SolveResult::direct_light), one value per patch.
  const std::vector<Rgb>& patch_direct;
};

struct Display {
  DisplayMesh mesh;
  DisplayStats stats;
};

// The patches' averages (no ray). Aborts when `radiosity` does not hold one value per patch.
DisplayMesh AveragedDisplay(const DisplayTopology& topology, const PatchScene& scene,
                            const std::vector<Rgb>& radiosity);

// The display with the direct light at its points. Aborts on per-patch inputs of the wrong size.
Display ShadeDisplay(const DisplayInput& input, const DisplaySettings& settings,
                     const DisplayProgress& progress = nullptr);

}  // namespace radfarm
