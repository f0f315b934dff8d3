#include "core/batch_tracer.h"

#include <algorithm>
#include <bit>
#include <cstdlib>
#include <new>
#include <optional>

namespace radfarm {
namespace {

// Sorts `keys` by their high 32 bits, all below 2^key_bits, by least-significant-digit radix
// passes of at most 11 bits (a counting table that stays in L1); `scratch` is reused. A long
// batch in a big scene has thousands of distinct patches, where comparison sorting cost about as
// much as counting its hits.
void SortByHighWord(std::vector<uint64_t>* keys, std::vector<uint64_t>* scratch,
                    uint32_t key_bits) {
  if (keys->size() < 64 || key_bits == 0) {
    std::sort(keys->begin(), keys->end());
    return;
  }
  const uint32_t passes = (key_bits + 10) / 11;
  const uint32_t digit_bits = (key_bits + passes - 1) / passes;
  const uint64_t mask = (uint64_t{1} << digit_bits) - 1;
  scratch->resize(keys->size());
  uint32_t counts[1u << 11];
  for (uint32_t pass = 0; pass < passes; ++pass) {
    const uint32_t shift = 32 + pass * digit_bits;
    std::fill_n(counts, mask + 1, 0u);
    for (uint64_t key : *keys) ++counts[(key >> shift) & mask];
    uint32_t start = 0;
    for (uint64_t digit = 0; digit <= mask; ++digit) {
      const uint32_t count = counts[digit];
      counts[digit] = start;
      start += count;
    }
    for (uint64_t key : *keys) (*scratch)[counts[(key >> shift) & mask]++] = key;
    keys->swap(*scratch);
  }
}

// A ray that left the scene or met a back face is counted in the result's escaped or back
// totals; false when it hit a front face (its weight is then the caller's to sum).
inline bool CountedAway(const RayHit& hit, uint64_t weight, BatchResult* result) {
  if (hit.patch == RayHit::kMiss) {
    result->escaped_weight += weight;
    ++result->escaped_rays;
    return true;
  }
  if (!hit.front) {
    result->back_weight += weight;
    ++result->back_rays;
    return true;
  }
  return false;
}

}  // namespace

BatchTracer::BatchTracer(const PatchScene& scene, const RayCaster& caster,
                         const RaySampler& sampler)
    : patches_(scene.patches.data()),
      patch_count_(scene.patches.size()),
      caster_(caster),
      sampler_(sampler),
      block_(std::make_unique<RayBlock>()),
      shot_block_(std::make_unique<RayBlock>()) {}

BatchTracer::BatchTracer(std::span<const PatchShape> shapes, const RayCaster& caster,
                         const RaySampler& sampler)
    : shapes_(shapes.data()),
      patch_count_(shapes.size()),
      caster_(caster),
      sampler_(sampler),
      block_(std::make_unique<RayBlock>()),
      shot_block_(std::make_unique<RayBlock>()) {}

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

BatchTracer::HitSum BatchTracer::HitSumFor(uint32_t ray_count) const {
  if (IsShort(ray_count)) return HitSum::kListed;
  if (patch_count_ <= kDenseMaxPatches) return HitSum::kDense;
  // The table: 12 bytes a slot, at most 4 slots a ray; the dense array: 8 bytes a patch.
  return uint64_t{48} * ray_count <= uint64_t{8} * patch_count_ ? HitSum::kHashed : HitSum::kDense;
}

void BatchTracer::PrepareTable(uint32_t ray_count) {
  size_t size = 64;
  while (size < 2 * size_t{ray_count}) size *= 2;
  if (slot_patch_.size() < size) {
    slot_patch_.assign(size, kEmptySlot);
    slot_weight_.assign(size, 0);
    slot_shift_ = 32 - static_cast<uint32_t>(std::countr_zero(size));
  }
}

void BatchTracer::AddHashed(uint32_t patch, uint64_t weight) {
  const size_t mask = slot_patch_.size() - 1;
  size_t slot = (patch * 0x9E3779B1u) >> slot_shift_;  // Fibonacci hashing
  while (true) {
    const uint32_t held = slot_patch_[slot];
    if (held == patch) {
      slot_weight_[slot] += weight;
      return;
    }
    if (held == kEmptySlot) {
      slot_patch_[slot] = patch;
      slot_weight_[slot] = weight;
      used_slots_.push_back(static_cast<uint32_t>(slot));
      return;
    }
    slot = (slot + 1) & mask;
  }
}

void BatchTracer::SumHashed(BatchResult* result) {
  // Sorted as (patch, slot) keys, plain integers, rather than as (patch, weight) records; the
  // patches are distinct, so their bits alone order the keys.
  slot_keys_.clear();
  for (uint32_t slot : used_slots_) slot_keys_.push_back(uint64_t{slot_patch_[slot]} << 32 | slot);
  SortByHighWord(&slot_keys_, &sort_scratch_,
                 static_cast<uint32_t>(std::bit_width(std::max<size_t>(patch_count_, 1) - 1)));
  result->hits.reserve(slot_keys_.size());
  for (uint64_t key : slot_keys_) {
    const auto slot = static_cast<uint32_t>(key);
    result->hits.push_back({slot_patch_[slot], slot_weight_[slot]});
    slot_patch_[slot] = kEmptySlot;
  }
  used_slots_.clear();
}

BatchResult BatchTracer::Run(const Batch& batch) {
  BatchResult result;
  const PatchShape& shooter = Shape(batch.shooter);
  const ShotSampler shot =
      sampler_.Shot(shooter, batch.shooter, batch.round, caster_.origin_offset());
  const HitSum sum = HitSumFor(batch.ray_count);
  uint64_t* const weight_by_patch = sum == HitSum::kDense ? WeightByPatch() : nullptr;
  // A long batch for the scene's patches is summed by a pass over the whole dense array
  // (SumDense), so it need not note the patches it touches.
  const bool note_touched = uint64_t{batch.ray_count} * 16 < patch_count_;
  if (sum == HitSum::kHashed) PrepareTable(batch.ray_count);
  RayBlock& block = *block_;
  RayHit hits[RayBlock::kSize];
  for (uint32_t done = 0; done < batch.ray_count; done += RayBlock::kSize) {
    const int count = static_cast<int>(std::min<uint32_t>(RayBlock::kSize, batch.ray_count - done));
    shot.SampleBlock(batch.first_ray + done, count, &block);
    caster_.TraceBlock(block, shooter.normal, hits);
    if (sum == HitSum::kDense && patch_count_ > kPrefetchMinPatches) {
      // Start the loads of the hit patches' weights before the loop below needs them.
      for (int i = 0; i < count; ++i) {
        if (hits[i].patch != RayHit::kMiss) __builtin_prefetch(&weight_by_patch[hits[i].patch]);
      }
    }
    for (int i = 0; i < count; ++i) {
      const RayHit hit = hits[i];
      const uint64_t weight = block.weight[i];
      if (CountedAway(hit, weight, &result)) continue;
      if (sum == HitSum::kListed) {
        if (weight != 0) listed_.push_back({hit.patch, weight});
      } else if (sum == HitSum::kHashed) {
        if (weight != 0) AddHashed(hit.patch, weight);
      } else {
        if (note_touched && weight_by_patch[hit.patch] == 0) touched_.push_back(hit.patch);
        weight_by_patch[hit.patch] += weight;
      }
    }
  }
  switch (sum) {
    case HitSum::kListed:
      SumListed(&result);
      break;
    case HitSum::kHashed:
      SumHashed(&result);
      break;
    case HitSum::kDense:
      SumDense(weight_by_patch, !note_touched, &result);
      // In a big scene only a batch too long for the table comes here: the array is not kept.
      if (patch_count_ > kDenseMaxPatches) weight_by_patch_.reset();
      break;
  }
  return result;
}

size_t BatchTracer::GroupEnd(std::span<const Batch> batches, size_t begin) {
  size_t end = begin + 1;
  if (!IsShort(batches[begin].ray_count)) return end;
  uint64_t rays = batches[begin].ray_count;
  while (end < batches.size() && IsShort(batches[end].ray_count) &&
         rays + batches[end].ray_count <= kGroupRays) {
    rays += batches[end].ray_count;
    ++end;
  }
  return end;
}

std::vector<size_t> BatchTracer::GroupStarts(std::span<const Batch> batches) {
  std::vector<size_t> starts = {0};
  while (starts.back() < batches.size()) starts.push_back(GroupEnd(batches, starts.back()));
  return starts;
}

void BatchTracer::RunMany(std::span<const Batch> batches, BatchResult* results) {
  size_t k = 0;
  while (k < batches.size()) {
    if (!IsShort(batches[k].ray_count)) {
      results[k] = Run(batches[k]);
      ++k;
      continue;
    }
    size_t end = k + 1;
    while (end < batches.size() && IsShort(batches[end].ray_count)) ++end;
    RunShort(batches.subspan(k, end - k), results + k);
    k = end;
  }
}

void BatchTracer::RunShort(std::span<const Batch> batches, BatchResult* results) {
  for (size_t k = 0; k < batches.size(); ++k) results[k] = BatchResult{};
  RayBlock& block = *block_;
  RayBlock& part = *shot_block_;
  Vec3 normals[RayBlock::kSize];    // of each ray's shooter, which lifts its origin
  uint32_t owner[RayBlock::kSize];  // each ray's batch
  RayHit hits[RayBlock::kSize];
  std::optional<ShotSampler> shot;
  size_t next = 0;       // the batch whose rays are sampled next
  uint32_t sampled = 0;  // of its rays
  size_t summing = 0;    // the first batch whose hits are not all summed
  while (next < batches.size()) {
    // A block of the next rays in batch order, a batch's rays as Run samples them.
    int filled = 0;
    while (filled < RayBlock::kSize && next < batches.size()) {
      const Batch& batch = batches[next];
      if (sampled == batch.ray_count) {  // done (or no rays at all)
        ++next;
        sampled = 0;
        continue;
      }
      const PatchShape& shooter = Shape(batch.shooter);
      if (sampled == 0)
        shot.emplace(sampler_.Shot(shooter, batch.shooter, batch.round, caster_.origin_offset()));
      const int take =
          static_cast<int>(std::min<uint32_t>(RayBlock::kSize - filled, batch.ray_count - sampled));
      shot->SampleBlock(batch.first_ray + sampled, take, &part);
      std::copy_n(part.origin_x, take, block.origin_x + filled);
      std::copy_n(part.origin_y, take, block.origin_y + filled);
      std::copy_n(part.origin_z, take, block.origin_z + filled);
      std::copy_n(part.direction_x, take, block.direction_x + filled);
      std::copy_n(part.direction_y, take, block.direction_y + filled);
      std::copy_n(part.direction_z, take, block.direction_z + filled);
      std::copy_n(part.weight, take, block.weight + filled);
      std::fill_n(normals + filled, take, shooter.normal);
      std::fill_n(owner + filled, take, static_cast<uint32_t>(next));
      filled += take;
      sampled += take;
    }
    if (filled == 0) break;
    block.count = filled;
    caster_.TraceBlock(block, normals, hits);
    for (int i = 0; i < filled; ++i) {
      // Batches before this ray's have all their rays summed: their lists are complete.
      for (; summing < owner[i]; ++summing) SumListed(&results[summing]);
      const uint64_t weight = block.weight[i];
      if (!CountedAway(hits[i], weight, &results[owner[i]]) && weight != 0) {
        listed_.push_back({hits[i].patch, weight});
      }
    }
  }
  for (; summing < batches.size(); ++summing) SumListed(&results[summing]);
}

void BatchTracer::SumDense(uint64_t* weight_by_patch, bool scan, BatchResult* result) {
  // The hits in patch order: one pass over the dense array when the batch is long against the
  // scene's patches (cheaper than sorting its many hits; it did not note them), else a sort of
  // the patches it touched.
  if (scan || touched_.size() * 16 >= patch_count_) {
    size_t distinct = 0;
    for (uint32_t patch = 0; patch < patch_count_; ++patch) distinct += weight_by_patch[patch] != 0;
    result->hits.reserve(distinct);
    for (uint32_t patch = 0; patch < patch_count_; ++patch) {
      if (weight_by_patch[patch] == 0) continue;
      result->hits.push_back({patch, weight_by_patch[patch]});
      weight_by_patch[patch] = 0;
    }
  } else {
    result->hits.reserve(touched_.size());
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
