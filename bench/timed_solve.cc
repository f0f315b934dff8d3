#include "bench/timed_solve.h"

#include <algorithm>

#include "bench/stopwatch.h"

namespace radfarm::bench {

TimedSolve RunTimedSolve(const PatchScene& scene, const SolverSettings& settings, int repetitions) {
  TimedSolve timed;
  for (int rep = 0; rep < std::max(1, repetitions); ++rep) {
    const Stopwatch clock;
    timed.result = Solve(scene, settings);
    timed.seconds.push_back(clock.Seconds());
  }
  timed.median_seconds = Median(timed.seconds);
  return timed;
}

}  // namespace radfarm::bench
