// PathTracer: an unbiased estimate of the outgoing radiance at surface points of a ReferenceScene,
// with its standard error: B = Le + rho / pi * integral of L cos over the hemisphere.
//
// Method: paths from the point; at every diffuse vertex, next-event estimation on one emitter
// triangle (picked by area times emitted radiance, a point uniform on it) and on every punctual
// lamp (one shadow ray each); then a cosine-weighted direction. An emitter hit by that direction
// and sampled by next-event estimation too is weighted by the balance heuristic (multiple
// importance sampling), so neither strategy counts it twice. A direction that leaves the scene
// takes the sky's luminance along it (core/sky.h; none without a sky). Russian roulette from the
// third bounce on (survival = the path's largest channel of throughput, at most 0.95), so paths
// have no length limit and no bias.
//
// Determinism: sample s of point i draws its numbers from CounterRng(HashWords(seed, i, s)), and a
// point's samples are summed in order, so the estimates depend on (scene, points, settings) only,
// not on threads.
//
// Stopping: a point takes blocks of `block` samples until its relative standard error (channel
// sum) is at most `relative_error` after at least `min_samples`, or it has `max_samples`. (Stopping
// on the estimated error biases by a fraction of the error; min_samples keeps that small.)
#pragma once

#include <cstdint>
#include <vector>

#include "core/rgb.h"
#include "core/vec3.h"
#include "reference/reference_scene.h"

namespace radfarm::reference {

struct SurfacePoint {
  Vec3 position;
  Vec3 normal;  // unit, the side whose outgoing radiance is wanted
  uint32_t triangle = 0;
};

struct TraceSettings {
  uint64_t seed = 1;
  double relative_error = 0.005;
  uint64_t min_samples = 1024;
  uint64_t max_samples = 1 << 20;
  uint64_t block = 256;
  unsigned threads = 2;
};

struct PointEstimate {
  Rgb radiance;
  Rgb standard_error;
  double relative_error = 0;  // standard error over the estimate, channel sum (0 when both are 0)
  uint64_t samples = 0;
  uint64_t rays = 0;  // closest-hit and shadow rays cast
};

class PathTracer {
 public:
  explicit PathTracer(const ReferenceScene& scene) : scene_(scene) {}

  // Point `index` (its place in a point list: part of the random key).
  PointEstimate Estimate(const SurfacePoint& point, uint64_t index,
                         const TraceSettings& settings) const;
  // Every point, on settings.threads threads; result i is Estimate(points[i], i, settings).
  std::vector<PointEstimate> EstimateAll(const std::vector<SurfacePoint>& points,
                                         const TraceSettings& settings) const;
  // The irradiance at a point in open space facing `normal` (a calculation point of an
  // illuminance report), as E / pi in the units of emitted radiance: the outgoing radiance a white
  // (rho = 1) surface there would have, less its emission. Keyed as Estimate.
  PointEstimate EstimateIrradiance(const Vec3& position, const Vec3& normal, uint64_t index,
                                   const TraceSettings& settings) const;
  // Every point (position and unit normal), on settings.threads threads.
  std::vector<PointEstimate> EstimateIrradianceAll(const std::vector<Vec3>& positions,
                                                   const std::vector<Vec3>& normals,
                                                   const TraceSettings& settings) const;

 private:
  // One path's contribution from x (normal n, on triangle `self` or none: SurfaceHit::kMiss) with
  // throughput `beta` at its start, beyond the point's own emission, and the rays it cast.
  Rgb SamplePath(Vec3 x, Vec3 n, uint32_t self, Rgb beta, uint64_t key, uint64_t* rays) const;
  // Samples `sample(key, &rays)` keyed (seed, index, s) in blocks until the stopping rule holds;
  // `own` is added to the mean.
  template <typename Sample>
  PointEstimate Accumulate(const Rgb& own, uint64_t index, const TraceSettings& settings,
                           const Sample& sample) const;
  // Next-event estimation on the emitter triangles at x (normal n, on triangle `self`), MIS
  // weighted; `dim` is the first random dimension it may use (three).
  Rgb SampleEmitters(const Vec3& x, const Vec3& n, uint32_t self, uint64_t key, uint32_t dim,
                     uint64_t* rays) const;
  // The punctual lamps' unoccluded irradiance at x, in the units of emitted radiance.
  Rgb PunctualIrradiance(const Vec3& x, const Vec3& n, uint64_t* rays) const;
  // The emitted radiance leaving a triangle on its front, or on its back (two-sided only).
  Rgb Emitted(uint32_t triangle, bool front) const;

  const ReferenceScene& scene_;
};

// The surface point at p whose side faces along n: the closest triangle found by a short ray from
// p + n h back along -n (h a small fraction of the scene), whose side facing n is the front or a
// two-sided material's back. Fails when no such triangle lies within 2 h.
Result<SurfacePoint> LocatePoint(const ReferenceScene& scene, const Vec3& p, const Vec3& n);

}  // namespace radfarm::reference
