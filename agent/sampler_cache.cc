#include "agent/sampler_cache.h"

#include <algorithm>
#include <bit>

namespace radfarm::agent {

std::shared_ptr<const RaySampler> SamplerCache::Get(SamplerKind kind, uint64_t seed,
                                                    double grid_step_degrees) {
  const uint64_t bits = std::bit_cast<uint64_t>(grid_step_degrees);
  auto found = std::find_if(entries_.begin(), entries_.end(), [&](const Entry& e) {
    return e.kind == kind && e.seed == seed && e.grid_step_bits == bits;
  });
  Entry entry;
  if (found != entries_.end()) {
    entry = *found;
    entries_.erase(found);
  } else {
    entry = {kind, seed, bits, std::make_shared<const RaySampler>(kind, seed, grid_step_degrees)};
  }
  entries_.push_front(entry);
  while (entries_.size() > capacity_) entries_.pop_back();
  return entry.sampler;
}

}  // namespace radfarm::agent
