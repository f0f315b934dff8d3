#include "bench/timed_solve.h"

#include <algorithm>

#include "bench/stopwatch.h"

namespace radfarm::bench {
void AddTimedRun(const PatchScene& scene, const SolverSettings& settings, TimedSolve* timed) {
  const Stopwatch clock;
  timed->result = Solve(scene, settings);
  timed->seconds.push_back(clock.Seconds());
  timed->median_seconds = Median(timed->seconds);
}

TimedSolve RunTimedSolve(const PatchScene& scene, const SolverSettings& settings, int repetitions) {
  TimedSolve timed;
  for (int rep = 0; rep < std::max(1, repetitions); ++rep) AddTimedRun(scene, settings, &timed);
  return timed;
}

std::pair<TimedSolve, TimedSolve> RunTimedPair(const PatchScene& scene, const SolverSettings& a,
                                               const SolverSettings& b, int repetitions) {
  std::pair<TimedSolve, TimedSolve> timed;
  for (int rep = 0; rep < std::max(1, repetitions); ++rep) {
    AddTimedRun(scene, a, &timed.first);
    AddTimedRun(scene, b, &timed.second);
  }
  return timed;
}

}  // namespace radfarm::bench
