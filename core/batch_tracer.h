// Computes batches: casts their rays and counts hits. Holds a per-thread scratch array, so use one
// BatchTracer per thread; the caster, sampler and scene are shared read-only.
#pragma once

#include <vector>

#include "core/batch.h"
#include "core/patch_scene.h"
#include "core/ray_caster.h"
#include "core/ray_sampler.h"

namespace radfarm {

class BatchTracer {
 public:
  BatchTracer(const PatchScene& scene, const RayCaster& caster, const RaySampler& sampler);

  BatchResult Run(const Batch& batch);

 private:
  const PatchScene& scene_;
  const RayCaster& caster_;
  const RaySampler& sampler_;
  std::vector<uint64_t> weight_by_patch_;  // dense scratch, all zero between calls
  std::vector<uint32_t> touched_;
};

}  // namespace radfarm
