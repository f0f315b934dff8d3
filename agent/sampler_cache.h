// SamplerCache: one RaySampler per (sampler kind, seed, grid step), the three assignment fields
// that define a job's rays (docs/PROTOCOL.md: "keeps one RaySampler per job"). A few recent ones
// are kept; batches hold theirs through a shared_ptr. Loop thread only.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <memory>

#include "core/ray_sampler.h"
#include "core/solver_settings.h"

namespace radfarm::agent {

class SamplerCache {
 public:
  explicit SamplerCache(size_t capacity = 8) : capacity_(capacity) {}

  std::shared_ptr<const RaySampler> Get(SamplerKind kind, uint64_t seed, double grid_step_degrees);

 private:
  struct Entry {
    SamplerKind kind;
    uint64_t seed;
    uint64_t grid_step_bits;  // compared as bits: the key is exact, like the wire value
    std::shared_ptr<const RaySampler> sampler;
  };
  size_t capacity_;
  std::deque<Entry> entries_;  // most recent first
};

}  // namespace radfarm::agent
