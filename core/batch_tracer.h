// Computes batches: casts their rays and counts hits. Holds per-thread scratch (a block of rays, a
// list of a short batch's hits, and a dense weight array made at the first long batch), so use one
// BatchTracer per thread; the caster, sampler and scene are
// shared read-only. A batch's rays are made and traced a RayBlock at a time (ray_sampler.h,
// ray_caster.h); the result is bit for bit that of sampling and tracing them one by one.
#pragma once

#include <cstdlib>
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

  // A batch of up to kListRays rays lists its front hits, (patch, weight) in ray order, and sums
  // them per patch after a sort: a list that stays in cache. A longer one adds into a dense array
  // of every patch, cheaper than sorting its many hits but a cache miss a hit in a big scene.
  static constexpr uint32_t kListRays = 256;
  uint64_t* WeightByPatch();  // the dense array, made (zeroed) on first use
  void SumDense(uint64_t* weight_by_patch, BatchResult* result);
  void SumListed(BatchResult* result);

  struct FreeDeleter {
    void operator()(uint64_t* p) const { std::free(p); }
  };

  const Patch* patches_ = nullptr;
  const PatchShape* shapes_ = nullptr;
  size_t patch_count_ = 0;
  const RayCaster& caster_;
  const RaySampler& sampler_;
  std::unique_ptr<RayBlock> block_;                           // scratch: the rays being traced
  std::unique_ptr<uint64_t[], FreeDeleter> weight_by_patch_;  // all zero between calls
  std::vector<uint32_t> touched_;
  std::vector<PatchHits> listed_;  // empty between calls
};

}  // namespace radfarm
