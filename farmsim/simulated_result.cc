#include "farmsim/simulated_result.h"

#include <algorithm>
#include <vector>

namespace radfarm::sim {
namespace {

uint64_t Mix(uint64_t x) {  // splitmix64's finaliser
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

// Up to `want` distinct patch ids other than the shooter, increasing.
std::vector<uint32_t> PickPatches(const protocol::AssignedBatch& b, uint32_t want) {
  std::vector<uint32_t> patches;
  if (b.patch_count == 1) return {0};
  want = std::min(want, b.patch_count - 1);
  uint64_t state = Mix(b.seed ^ Mix(b.round ^ Mix(uint64_t{b.shooter} ^ Mix(b.first_ray))));
  while (patches.size() < want) {
    state = Mix(state);
    const auto patch = static_cast<uint32_t>(state % b.patch_count);
    if (patch == b.shooter || std::find(patches.begin(), patches.end(), patch) != patches.end()) {
      continue;
    }
    patches.push_back(patch);
  }
  std::sort(patches.begin(), patches.end());
  return patches;
}

}  // namespace

Result<protocol::BatchOutcome> MakeSimulatedResult(const protocol::AssignedBatch& batch,
                                                   uint32_t spread, double compute_seconds) {
  if (batch.sampler == SamplerKind::kGrid) {
    return Error{
        "the simulator cannot answer grid-sampler batches (their weights depend on the "
        "ray directions); submit a sobol or random job"};
  }
  const std::vector<uint32_t> patches =
      PickPatches(batch, std::clamp<uint32_t>(std::min(spread, batch.ray_count), 1, spread));
  protocol::BatchOutcome result;
  result.lease = batch.lease;
  result.compute_seconds = compute_seconds;
  const uint64_t share = batch.ray_count / patches.size();
  uint64_t extra = batch.ray_count % patches.size();
  for (uint32_t patch : patches) {
    const uint64_t weight = share + (extra > 0 ? 1 : 0);
    if (extra > 0) --extra;
    result.hits.push_back({patch, weight});
  }
  return result;
}

}  // namespace radfarm::sim
