// How much a ray of the final gather costs against a ray of a shooting round, on this machine:
// the ETA (core/progress_estimator.h) prices the gather, most of a job's rays, at the shooting
// rounds' measured rate times this ratio. The two kinds differ by where their rays start: a
// shooting round's rays leave the brightest patches in proportion to their power, the gather's
// leave every reflecting patch alike, and one can cost well under the other on one scene and as
// much on another: priced alike, the ETA is far off.
//
// The probe: a sample of each kind (every k-th batch of the shooting plan, every k-th
// reflecting patch's gather shot), traced by the caller as it traces rounds (on the same threads,
// so contention between them counts as it will), alternating, each kind's best of a few passes.
// The results are thrown away: a ray's fate is a pure function of (seed, round, shooter, ray),
// so tracing it once more changes nothing.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "core/batch.h"
#include "core/patch_scene.h"

namespace radfarm {

struct RoundPlan;

struct RayCostProbe {
  uint64_t rays_per_kind = 16384;  // about; whole batches and whole gather shots
  int passes = 2;
};

struct RayCostSamples {
  std::vector<Batch> shooting, gather;
  uint64_t shooting_rays = 0, gather_rays = 0;
};

// About `rays_per_kind` rays of `shooting` (a shooting round's plan) and of the final gather,
// which casts `gather_rays` rays from each reflecting patch in batches of `batch_rays`.
RayCostSamples SampleRayCosts(const PatchScene& scene, const RoundPlan& shooting,
                              uint64_t gather_rays, uint32_t batch_rays, uint64_t rays_per_kind);

// Traces the batches (results discarded) and returns when all are done.
using RayCostTracer = std::function<void(const std::vector<Batch>&)>;

// Seconds per gather ray over seconds per shooting ray; nullopt when a sample is empty or too
// fast to time.
std::optional<double> GatherRayCostRatio(const RayCostSamples& samples, const RayCostTracer& trace,
                                         int passes);

}  // namespace radfarm
