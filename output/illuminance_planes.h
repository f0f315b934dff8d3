// An illuminance report's planes measured on a solution: each plane's carrying surfaces picked by
// name, its grid laid (output/illuminance_grid.h) and the lux at its points
// (output/illuminance_light.h).
#pragma once

#include <cstdint>
#include <vector>

#include "base/result.h"
#include "core/patch_scene.h"
#include "input/input_scene.h"
#include "output/illuminance_light.h"
#include "output/illuminance_plane.h"
#include "output/illuminance_report.h"

namespace radfarm {

// Per patch, whether `plane.surfaces` names its object (`objects[patch_object[patch]]`) or its
// material (fnmatch patterns); all true when the plane names none. Fails on a pattern that names
// no object and no material, naming the plane and the pattern.
Result<std::vector<bool>> SurfacesNamed(const IlluminancePlane& plane, const PatchScene& scene,
                                        const std::vector<InputObject>& objects,
                                        const std::vector<uint32_t>& patch_object);

// Every plane of `planes`, in order. The lux is a pure function of the solution and the planes,
// whatever the threads.
Result<std::vector<PlaneIlluminance>> MeasurePlanes(const IlluminanceSolution& solution,
                                                    const std::vector<InputObject>& objects,
                                                    const std::vector<uint32_t>& patch_object,
                                                    const std::vector<IlluminancePlane>& planes);

}  // namespace radfarm
