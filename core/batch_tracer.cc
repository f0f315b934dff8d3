#include "core/batch_tracer.h"

#include <algorithm>
#include <cstdlib>
#include <new>

namespace radfarm {

BatchTracer::BatchTracer(const PatchScene& scene, const RayCaster& caster,
                         const RaySampler& sampler)
    : patches_(scene.patches.data()),
      patch_count_(scene.patches.size()),
      caster_(caster),
      sampler_(sampler),
      block_(std::make_unique<RayBlock>()) {}

BatchTracer::BatchTracer(std::span<const PatchShape> shapes, const RayCaster& caster,
                         const RaySampler& sampler)
    : shapes_(shapes.data()),
      patch_count_(shapes.size()),
      caster_(caster),
      sampler_(sampler),
      block_(std::make_unique<RayBlock>()) {}

uint64_t* BatchTracer::WeightByPatch() {
  if (!weight_by_patch_) {
    // calloc: the kernel's zero pages, touched only where hits land, instead of a memset of the
    // whole array (8 MB at 10^6 patches) by a tracer made for a few batches (the master's checks).
    auto* weights = static_cast<uint64_t*>(std::calloc(std::max<size_t>(patch_count_, 1), 8));
    if (weights == nullptr) throw std::bad_alloc();
    weight_by_patch_.reset(weights);
  }
  return weight_by_patch_.get();
}

BatchResult BatchTracer::Run(const Batch& batch) {
  BatchResult result;
  const PatchShape& shooter = Shape(batch.shooter);
  const ShotSampler shot =
      sampler_.Shot(shooter, batch.shooter, batch.round, caster_.origin_offset());
  const bool listed = batch.ray_count <= kListRays;
  uint64_t* const weight_by_patch = listed ? nullptr : WeightByPatch();
  RayBlock& block = *block_;
  RayHit hits[RayBlock::kSize];
  for (uint32_t done = 0; done < batch.ray_count; done += RayBlock::kSize) {
    const int count = static_cast<int>(std::min<uint32_t>(RayBlock::kSize, batch.ray_count - done));
    shot.SampleBlock(batch.first_ray + done, count, &block);
    caster_.TraceBlock(block, shooter.normal, hits);
    if (!listed) {
      // Start the loads of the hit patches' weights before the loop below needs them.
      for (int i = 0; i < count; ++i) {
        if (hits[i].patch != RayHit::kMiss) __builtin_prefetch(&weight_by_patch[hits[i].patch]);
      }
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
      } else if (listed) {
        if (weight != 0) listed_.push_back({hit.patch, weight});
      } else {
        if (weight_by_patch[hit.patch] == 0) touched_.push_back(hit.patch);
        weight_by_patch[hit.patch] += weight;
      }
    }
  }
  if (listed) {
    SumListed(&result);
  } else {
    SumDense(weight_by_patch, &result);
  }
  return result;
}

void BatchTracer::SumDense(uint64_t* weight_by_patch, BatchResult* result) {
  result->hits.reserve(touched_.size());
  // The hits in patch order: a sort of the touched patches, or, when they are many against the
  // scene's patches (a long batch in a small scene), one pass over the dense array, which is
  // cheaper than sorting them.
  if (touched_.size() * 16 >= patch_count_) {
    for (uint32_t patch = 0; patch < patch_count_; ++patch) {
      if (weight_by_patch[patch] == 0) continue;
      result->hits.push_back({patch, weight_by_patch[patch]});
      weight_by_patch[patch] = 0;
    }
  } else {
    std::sort(touched_.begin(), touched_.end());
    for (uint32_t patch : touched_) {
      result->hits.push_back({patch, weight_by_patch[patch]});
      weight_by_patch[patch] = 0;
    }
  }
  touched_.clear();
}

void BatchTracer::SumListed(BatchResult* result) {
  // The order within a patch does not matter: its weights are summed as integers.
  const auto by_patch = [](const PatchHits& a, const PatchHits& b) { return a.patch < b.patch; };
  if (listed_.size() <= 32) {  // insertion sort: cheaper than std::sort's set-up for a few
    for (size_t i = 1; i < listed_.size(); ++i) {
      const PatchHits item = listed_[i];
      size_t j = i;
      for (; j > 0 && by_patch(item, listed_[j - 1]); --j) listed_[j] = listed_[j - 1];
      listed_[j] = item;
    }
  } else {
    std::sort(listed_.begin(), listed_.end(), by_patch);
  }
  size_t distinct = 0;
  for (size_t i = 0; i < listed_.size(); ++i) {
    distinct += i == 0 || listed_[i].patch != listed_[i - 1].patch;
  }
  result->hits.reserve(distinct);
  for (const PatchHits& item : listed_) {
    if (!result->hits.empty() && result->hits.back().patch == item.patch) {
      result->hits.back().weight += item.weight;
    } else {
      result->hits.push_back(item);
    }
  }
  listed_.clear();
}

}  // namespace radfarm
