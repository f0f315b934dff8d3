#include "core/batch_tracer.h"

#include <algorithm>

namespace radfarm {

BatchTracer::BatchTracer(const PatchScene& scene, const RayCaster& caster,
                         const RaySampler& sampler)
    : patches_(scene.patches.data()),
      caster_(caster),
      sampler_(sampler),
      block_(std::make_unique<RayBlock>()),
      weight_by_patch_(scene.patches.size()) {}

BatchTracer::BatchTracer(std::span<const PatchShape> shapes, const RayCaster& caster,
                         const RaySampler& sampler)
    : shapes_(shapes.data()),
      caster_(caster),
      sampler_(sampler),
      block_(std::make_unique<RayBlock>()),
      weight_by_patch_(shapes.size()) {}

BatchResult BatchTracer::Run(const Batch& batch) {
  BatchResult result;
  const PatchShape& shooter = Shape(batch.shooter);
  const ShotSampler shot =
      sampler_.Shot(shooter, batch.shooter, batch.round, caster_.origin_offset());
  RayBlock& block = *block_;
  RayHit hits[RayBlock::kSize];
  for (uint32_t done = 0; done < batch.ray_count; done += RayBlock::kSize) {
    const int count = static_cast<int>(std::min<uint32_t>(RayBlock::kSize, batch.ray_count - done));
    shot.SampleBlock(batch.first_ray + done, count, &block);
    caster_.TraceBlock(block, shooter.normal, hits);
    // Start the loads of the hit patches' weights before the loop below needs them.
    for (int i = 0; i < count; ++i) {
      if (hits[i].patch != RayHit::kMiss) __builtin_prefetch(&weight_by_patch_[hits[i].patch]);
    }
    for (int i = 0; i < count; ++i) {
      const RayHit hit = hits[i];
      const uint64_t weight = block.weight[i];
      if (hit.patch == RayHit::kMiss) {
        result.escaped_weight += weight;
        ++result.escaped_rays;
      } else if (!hit.front) {
        result.back_weight += weight;
        ++result.back_rays;
      } else {
        if (weight_by_patch_[hit.patch] == 0) touched_.push_back(hit.patch);
        weight_by_patch_[hit.patch] += weight;
      }
    }
  }
  result.hits.reserve(touched_.size());
  // The hits in patch order: a sort of the touched patches, or, when they are many against the
  // scene's patches (a long batch in a small scene), one pass over the dense array, which is
  // cheaper than sorting them.
  if (touched_.size() * 16 >= weight_by_patch_.size()) {
    for (uint32_t patch = 0; patch < weight_by_patch_.size(); ++patch) {
      if (weight_by_patch_[patch] == 0) continue;
      result.hits.push_back({patch, weight_by_patch_[patch]});
      weight_by_patch_[patch] = 0;
    }
  } else {
    std::sort(touched_.begin(), touched_.end());
    for (uint32_t patch : touched_) {
      result.hits.push_back({patch, weight_by_patch_[patch]});
      weight_by_patch_[patch] = 0;
    }
  }
  touched_.clear();
  return result;
}

}  // namespace radfarm
