#include "base/latency_histogram.h"

namespace radfarm {

void LatencyHistogram::Record(double seconds) {
  for (size_t i = 0; i < kBounds.size(); ++i) {
    if (seconds <= kBounds[i]) {
      ++buckets_[i];
      break;
    }
  }
  ++count_;
  sum_ += seconds;
}

uint64_t LatencyHistogram::CountAtMost(size_t bound) const {
  uint64_t total = 0;
  for (size_t i = 0; i <= bound && i < buckets_.size(); ++i) total += buckets_[i];
  return total;
}

}  // namespace radfarm
