// Computes batches: casts their rays and counts hits. Holds per-thread scratch (a block of rays, a
// list of a short batch's hits, and a dense weight array made at the first long batch of a small
// scene or a hash table sized to the batches of a big one), so use one
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
  // results[k] = Run(batches[k]) for every k, bit for bit (`results` holds batches.size()).
  // Consecutive short batches (a big scene's weak shooters cast a dozen rays each) share blocks
  // of rays, so their rays fill Embree's packets and a block's fixed costs are paid once for
  // several of them.
  void RunMany(std::span<const Batch> batches, BatchResult* results);

  // Where the group of batches that starts at batches[begin] ends, for callers that hand work
  // to threads a group at a time and call RunMany on each: a run of short batches of at most
  // kGroupRays rays in all, or one longer batch alone.
  static size_t GroupEnd(std::span<const Batch> batches, size_t begin);
  // The first batch of every group, in order, then batches.size().
  static std::vector<size_t> GroupStarts(std::span<const Batch> batches);
  static constexpr uint32_t kGroupRays = 256;

 private:
  // The shooter's shape: patches_[id] or shapes_[id], whichever was given.
  const PatchShape& Shape(uint32_t id) const { return patches_ ? patches_[id] : shapes_[id]; }

  // How a batch's front hits are summed per patch (all three give the same result):
  //  - kListed: a batch of up to kListRays rays lists them, (patch, weight) in ray order, and sums
  //    them after a sort: a list that stays in cache.
  //  - kDense: a longer one adds into a dense array of every patch, cheaper than sorting its many
  //    hits, in a scene of at most kDenseMaxPatches patches (the array stays in cache).
  //  - kHashed: in a bigger scene the dense array would cost a cache miss a hit and 8 bytes a
  //    patch for each tracer (an agent's budget is about 300 bytes a patch, threads included), so
  //    the hits are summed in a small open-addressing table sized to the batch, whose distinct
  //    patches are sorted at the end. A batch whose table would outgrow the dense array uses the
  //    dense array after all, made for it and freed after it.
  enum class HitSum { kListed, kDense, kHashed };
  static constexpr uint32_t kListRays = 256;
  // A batch summed as a list (kListed), which RunMany traces with its neighbours.
  static bool IsShort(uint32_t ray_count) { return ray_count <= kListRays; }
  static constexpr size_t kDenseMaxPatches = size_t{1} << 16;
  // Below this many patches the dense array (8 bytes a patch) stays in L1: prefetching its
  // entries before adding to them only costs.
  static constexpr size_t kPrefetchMinPatches = 4096;
  HitSum HitSumFor(uint32_t ray_count) const;
  // RunMany's run of consecutive kListed batches.
  void RunShort(std::span<const Batch> batches, BatchResult* results);
  uint64_t* WeightByPatch();  // the dense array, made (zeroed) on first use
  void SumDense(uint64_t* weight_by_patch, bool scan, BatchResult* result);
  void SumListed(BatchResult* result);
  // The hash table: slots for at least twice `ray_count` distinct patches, all empty.
  void PrepareTable(uint32_t ray_count);
  void AddHashed(uint32_t patch, uint64_t weight);
  void SumHashed(BatchResult* result);

  struct FreeDeleter {
    void operator()(uint64_t* p) const { std::free(p); }
  };

  const Patch* patches_ = nullptr;
  const PatchShape* shapes_ = nullptr;
  size_t patch_count_ = 0;
  const RayCaster& caster_;
  const RaySampler& sampler_;
  std::unique_ptr<RayBlock> block_;                           // scratch: the rays being traced
  std::unique_ptr<RayBlock> shot_block_;  // RunShort's scratch: one shot's part of block_
  std::unique_ptr<uint64_t[], FreeDeleter> weight_by_patch_;  // all zero between calls
  std::vector<uint32_t> touched_;
  std::vector<PatchHits> listed_;  // empty between calls
  // kHashed: slot_patch_ kEmptySlot where free (all free between calls), the slots in use in
  // used_slots_; a power-of-two size, grown as batches need and kept.
  static constexpr uint32_t kEmptySlot = 0xFFFFFFFFu;
  std::vector<uint32_t> slot_patch_;
  std::vector<uint64_t> slot_weight_;
  std::vector<uint32_t> used_slots_;
  std::vector<uint64_t> slot_keys_;     // SumHashed's scratch
  std::vector<uint64_t> sort_scratch_;  // and its sort's
  uint32_t slot_shift_ = 32;         // 32 - log2(table size)
};

}  // namespace radfarm
