// Metering that ignores the light sources: auto exposure set from the lit surfaces only. Metering
// the final image instead lets a large emitter in view (a ceiling light seen from inside a room)
// set the exposure and leave the walls near black.
#pragma once

#include <vector>

#include "display/display_mesh.h"
#include "output/camera.h"

namespace radfarm {

// `camera` with auto exposure resolved: when camera.auto_exposure, exposure becomes the stops that
// map the 99th-percentile luminance of the non-emitter surfaces in view to white, plus
// camera.exposure as compensation; otherwise `camera` unchanged. `emitter_patch[p]` is true for
// patches that emit; `camera` must be resolved (not automatic).
Camera MeterExposure(const DisplayMesh& mesh, const std::vector<bool>& emitter_patch,
                     const Camera& camera);

}  // namespace radfarm
