// Points spread area-uniformly over a ReferenceScene's surfaces, from a fixed seed: the places
// where the display is scored. A two-sided surface gives either side with equal chance; a
// one-sided one its front.
#pragma once

#include <cstdint>
#include <vector>

#include "bench/reference/path_tracer.h"
#include "bench/reference/reference_scene.h"

namespace radfarm::reference {

// `count` points; point i is a pure function of (scene, seed, i).
std::vector<SurfacePoint> SampleSurfacePoints(const ReferenceScene& scene, uint32_t count,
                                              uint64_t seed);

}  // namespace radfarm::reference
