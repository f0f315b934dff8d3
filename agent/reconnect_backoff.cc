#include "agent/reconnect_backoff.h"

#include <algorithm>

namespace radfarm::agent {

ReconnectBackoff::ReconnectBackoff(Options options, uint64_t seed)
    : options_(options), base_(options.initial), random_(seed) {
  options_.initial = std::max(options_.initial, std::chrono::milliseconds(1));
  options_.cap = std::max(options_.cap, options_.initial);
  base_ = options_.initial;
}

std::chrono::milliseconds ReconnectBackoff::Next() {
  const int64_t base = base_.count();
  std::uniform_int_distribution<int64_t> jitter(base / 2, base);
  const std::chrono::milliseconds delay(jitter(random_));
  base_ = std::min(base_ * 2, options_.cap);
  return delay;
}

void ReconnectBackoff::Reset() { base_ = options_.initial; }

}  // namespace radfarm::agent
