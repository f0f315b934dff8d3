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

}  // namespace radfarm
