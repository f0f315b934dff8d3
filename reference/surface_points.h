// Points spread area-uniformly over a ReferenceScene's surfaces, from a fixed seed: the places
// where the display is scored. A two-sided surface gives either side with equal chance; a
// one-sided one its front.
#pragma once

#include <cstdint>
#include <vector>

#include "reference/path_tracer.h"
#include "reference/reference_scene.h"

namespace radfarm::reference {

// `count` points; point i is a pure function of (scene, seed, i).
std::vector<SurfacePoint> SampleSurfacePoints(const ReferenceScene& scene, uint32_t count,
                                              uint64_t seed);

// Whether another surface lies within `band` of the point on its side: one of kBandProbes fixed
// directions over the hemisphere (the same for every point) meets a surface closer than `band`.
// Contact lines, corners, the slit above a hanging lamp and the ground beside a block are near.
bool NearAnotherSurface(const ReferenceScene& scene, const SurfacePoint& point, double band);
inline constexpr uint32_t kBandProbes = 64;
// The nearest of those probes' hits closer than `band`; a miss (SurfaceHit::kMiss) when none is.
SurfaceHit NearestSurfaceWithin(const ReferenceScene& scene, const SurfacePoint& point,
                                double band);

// `count` points area-uniform over the part of the surfaces near another (NearAnotherSurface):
// area-uniform candidates (seeded apart from SampleSurfacePoints') kept when near, up to
// `max_candidates` tried; fewer than `count` when the band is that rare.
std::vector<SurfacePoint> SampleBandPoints(const ReferenceScene& scene, uint32_t count,
                                           uint64_t seed, double band,
                                           uint64_t max_candidates = 1 << 22);

}  // namespace radfarm::reference
