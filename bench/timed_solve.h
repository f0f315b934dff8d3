// Runs Solve() repeatedly and keeps the median wall time. Solve is deterministic, so every
// repetition gives the same solution; only the time varies.
#pragma once

#include <utility>
#include <vector>

#include "core/patch_scene.h"
#include "solve/local_solve.h"
#include "core/solver_settings.h"

namespace radfarm::bench {

struct TimedSolve {
  SolveResult result;  // of the last repetition (all are identical)
  // Wall time of each repetition: Solve() as called, BVH build included.
  std::vector<double> seconds;
  double median_seconds = 0;
};

// Runs one more repetition into `timed` and updates its median.
void AddTimedRun(const PatchScene& scene, const SolverSettings& settings, TimedSolve* timed);

TimedSolve RunTimedSolve(const PatchScene& scene, const SolverSettings& settings, int repetitions);

// Times two settings alternately (a, b, a, b, ...), so that both see the same machine load: for
// comparisons of two times on a shared machine.
std::pair<TimedSolve, TimedSolve> RunTimedPair(const PatchScene& scene, const SolverSettings& a,
                                               const SolverSettings& b, int repetitions);

}  // namespace radfarm::bench
