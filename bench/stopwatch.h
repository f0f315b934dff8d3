// Wall-clock timing and the statistics the benchmark quotes: the machine is shared, so single
// timings are noise and every figure is a median of repeated runs.
#pragma once

#include <algorithm>
#include <chrono>
#include <vector>

namespace radfarm::bench {

class Stopwatch {
 public:
  Stopwatch() : start_(std::chrono::steady_clock::now()) {}
  double Seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

 private:
  std::chrono::steady_clock::time_point start_;
};

// Median of a non-empty sample (mean of the two middle values for an even count).
inline double Median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const size_t n = values.size();
  return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

}  // namespace radfarm::bench
