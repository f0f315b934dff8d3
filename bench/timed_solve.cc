#include "bench/timed_solve.h"

#include <algorithm>

#include "bench/stopwatch.h"

namespace radfarm::bench {
namespace {

void RunOnce(const PatchScene& scene, const SolverSettings& settings, TimedSolve* timed) {
  const Stopwatch clock;
  timed->result = Solve(scene, settings);
  timed->seconds.push_back(clock.Seconds());
  timed->median_seconds = Median(timed->seconds);
}

}  // namespace

TimedSolve RunTimedSolve(const PatchScene& scene, const SolverSettings& settings, int repetitions) {
  TimedSolve timed;
  for (int rep = 0; rep < std::max(1, repetitions); ++rep) RunOnce(scene, settings, &timed);
  return timed;
}

std::pair<TimedSolve, TimedSolve> RunTimedPair(const PatchScene& scene, const SolverSettings& a,
                                               const SolverSettings& b, int repetitions) {
  std::pair<TimedSolve, TimedSolve> timed;
  for (int rep = 0; rep < std::max(1, repetitions); ++rep) {
    RunOnce(scene, a, &timed.first);
    RunOnce(scene, b, &timed.second);
  }
  return timed;
}

}  // namespace radfarm::bench
