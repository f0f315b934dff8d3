#include "agent/throughput_meter.h"

#include <cmath>

namespace radfarm::agent {

void ThroughputMeter::Add(uint64_t rays, double compute_seconds) {
  if (!std::isfinite(compute_seconds) || compute_seconds < 0) return;
  samples_.push_back({rays, compute_seconds});
  while (samples_.size() > window_) samples_.pop_front();
}

double ThroughputMeter::RaysPerSecond() const {
  double rays = 0, seconds = 0;  // summed afresh: a running sum would drift as samples leave
  for (const Sample& sample : samples_) {
    rays += static_cast<double>(sample.rays);
    seconds += sample.seconds;
  }
  if (seconds <= 0) return 0;
  const double rate = static_cast<double>(threads_) * rays / seconds / slowdown_;
  return std::isfinite(rate) ? rate : 0;
}

}  // namespace radfarm::agent
