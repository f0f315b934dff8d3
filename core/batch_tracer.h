// Computes batches: casts their rays and counts hits. Holds per-thread scratch (a block of rays and
// a dense weight array), so use one BatchTracer per thread; the caster, sampler and scene are
// shared read-only. A batch's rays are made and traced a RayBlock at a time (ray_sampler.h,
// ray_caster.h); the result is bit for bit that of sampling and tracing them one by one.
#pragma once

#include <memory>
#include <span>
#include <vector>

#include "core/batch.h"
#include "core/patch_scene.h"
#include "core/ray_caster.h"
#include "core/ray_sampler.h"

namespace radfarm {

class BatchTracer {
 public:
  BatchTracer(const PatchScene& scene, const RayCaster& caster, const RaySampler& sampler);
  // For an agent, which keeps only its patches' shapes (agent/prepared_scene.h).
  BatchTracer(std::span<const PatchShape> shapes, const RayCaster& caster,
              const RaySampler& sampler);

  BatchResult Run(const Batch& batch);

 private:
  // The shooter's shape: patches_[id] or shapes_[id], whichever was given.
  const PatchShape& Shape(uint32_t id) const { return patches_ ? patches_[id] : shapes_[id]; }

  const Patch* patches_ = nullptr;
  const PatchShape* shapes_ = nullptr;
  const RayCaster& caster_;
  const RaySampler& sampler_;
  std::unique_ptr<RayBlock> block_;        // scratch: the rays being traced
  std::vector<uint64_t> weight_by_patch_;  // dense scratch, all zero between calls
  std::vector<uint32_t> touched_;
};

}  // namespace radfarm
