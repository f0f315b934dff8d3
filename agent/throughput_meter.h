// ThroughputMeter: the rays per second the agent reports in its heartbeats, measured over its most
// recent batches: threads x (rays / compute seconds) of the last `window` batches, divided by the
// --slowdown factor (a slowed agent delivers that much less). 0 before the first batch.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>

namespace radfarm::agent {

class ThroughputMeter {
 public:
  ThroughputMeter(unsigned threads, double slowdown, size_t window = 32)
      : threads_(threads), slowdown_(slowdown), window_(window) {}

  void Add(uint64_t rays, double compute_seconds);
  double RaysPerSecond() const;

 private:
  struct Sample {
    uint64_t rays;
    double seconds;
  };
  unsigned threads_;
  double slowdown_;
  size_t window_;
  std::deque<Sample> samples_;  // oldest first
};

}  // namespace radfarm::agent
