#include "core/batch_tracer.h"

#include <algorithm>

namespace radfarm {

BatchTracer::BatchTracer(const PatchScene& scene, const RayCaster& caster,
                         const RaySampler& sampler)
    : scene_(scene), caster_(caster), sampler_(sampler), weight_by_patch_(scene.patches.size()) {}

BatchResult BatchTracer::Run(const Batch& batch) {
  BatchResult result;
  const Patch& shooter = scene_.patches[batch.shooter];
  const ShotSampler shot = sampler_.Shot(shooter, batch.shooter, batch.round);
  for (uint64_t k = batch.first_ray; k < batch.first_ray + batch.ray_count; ++k) {
    const RaySample ray = shot.Sample(k);
    const RayHit hit = caster_.Trace(ray.origin, ray.direction, shooter.normal);
    if (hit.patch == RayHit::kMiss) {
      result.escaped_weight += ray.weight;
      ++result.escaped_rays;
    } else if (!hit.front) {
      result.back_weight += ray.weight;
      ++result.back_rays;
    } else {
      if (weight_by_patch_[hit.patch] == 0) touched_.push_back(hit.patch);
      weight_by_patch_[hit.patch] += ray.weight;
    }
  }
  std::sort(touched_.begin(), touched_.end());
  result.hits.reserve(touched_.size());
  for (uint32_t patch : touched_) {
    result.hits.push_back({patch, weight_by_patch_[patch]});
    weight_by_patch_[patch] = 0;
  }
  touched_.clear();
  return result;
}

}  // namespace radfarm
