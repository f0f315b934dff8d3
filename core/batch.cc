#include "core/batch.h"

#include <algorithm>

namespace radfarm {

void AppendShotBatches(uint32_t round, uint32_t shooter, uint64_t rays, uint32_t batch_rays,
                       std::vector<Batch>* batches) {
  for (uint64_t first = 0; first < rays; first += batch_rays) {
    const auto count = static_cast<uint32_t>(std::min<uint64_t>(batch_rays, rays - first));
    batches->push_back({round, shooter, first, count});
  }
}

uint32_t TaperFloor(uint32_t batch_rays) { return std::max<uint32_t>(1, batch_rays / 16); }

void TaperBatches(uint32_t ways, uint32_t floor, std::vector<Batch>* batches) {
  if (ways == 0 || batches->empty()) return;
  floor = std::max<uint32_t>(floor, 1);
  // The rays after a position are the same however the batches before it are cut: the first
  // batch to cut is found, and only the batches from it on are rebuilt.
  const auto limit = [&](uint64_t after) { return std::max<uint64_t>(floor, after / ways); };
  std::vector<Batch>& plan = *batches;
  uint64_t after = 0;
  size_t first_cut = plan.size();
  for (size_t k = plan.size(); k-- > 0;) {
    if (plan[k].ray_count > limit(after)) first_cut = k;
    after += plan[k].ray_count;
    // Batches past this point would fit whole: every later limit is larger still.
    if (after / ways >= uint64_t{1} << 32) break;
  }
  if (first_cut == plan.size()) return;
  std::vector<Batch> tail;  // the re-cut batches, last first
  uint64_t behind = 0;      // the rays after the next piece
  for (size_t k = plan.size(); k-- > first_cut;) {
    const Batch& batch = plan[k];
    uint64_t left = batch.ray_count;
    while (left > 0) {
      uint64_t piece = std::min(left, limit(behind));
      if (left - piece < floor) piece = left;  // a remainder under the floor joins this piece
      left -= piece;
      tail.push_back(
          {batch.round, batch.shooter, batch.first_ray + left, static_cast<uint32_t>(piece)});
      behind += piece;
    }
  }
  plan.resize(first_cut);
  plan.insert(plan.end(), tail.rbegin(), tail.rend());
}

}  // namespace radfarm
