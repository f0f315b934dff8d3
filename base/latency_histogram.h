// LatencyHistogram: a Prometheus-style histogram of durations (cumulative buckets, a sum and a
// count), such as the master's checkpoint latency that daemon/jobs records and /metrics prints.
// Plain value type: one thread records, readers get a copy.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

namespace radfarm {

class LatencyHistogram {
 public:
  // Upper bounds in seconds; the +Inf bucket is implied.
  static constexpr std::array<double, 11> kBounds = {0.005, 0.01, 0.025, 0.05, 0.1, 0.25,
                                                     0.5,   1,    2.5,   5,    10};

  void Record(double seconds);
  // Observations at most kBounds[i] seconds (cumulative, as Prometheus wants them).
  uint64_t CountAtMost(size_t bound) const;
  uint64_t count() const { return count_; }
  double sum() const { return sum_; }

 private:
  std::array<uint64_t, kBounds.size()> buckets_{};  // not cumulative: observations per bucket
  uint64_t count_ = 0;
  double sum_ = 0;
};

}  // namespace radfarm
