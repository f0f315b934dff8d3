// What the Gouraud image shows of each patch on average: the area-weighted mean of the radiance
// interpolated linearly over the patch's display triangles; and the step the display
// (display/display_stage.h) takes so that it matches the patch's mean light.
#pragma once

#include <cstddef>
#include <vector>

#include "core/rgb.h"
#include "display/display_mesh.h"

namespace radfarm {

// Per patch (0 .. patches - 1), the mean over its triangles of display.radiance interpolated
// linearly; zero for a patch with no triangle of positive area.
std::vector<Rgb> GouraudPatchMeans(const DisplayMesh& display, size_t patches);

// One step toward target: every vertex moves by the average of (target - GouraudPatchMeans) over
// the triangles that use it, weighted by their area. Patches with moves[f] false count as short
// by nothing (an emitter shows its emission). One step only: it removes most of the bias of
// linear interpolation, and further steps chase the noise in the targets. A channel the step would
// take below zero stays at zero.
// Points marked in `held` (when not empty) keep their value.
void StepTowardPatchMeans(DisplayMesh* display, const std::vector<Rgb>& target,
                          const std::vector<bool>& moves, const std::vector<bool>& held = {});

}  // namespace radfarm
