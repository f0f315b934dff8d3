// Runs Solve() repeatedly and keeps the median wall time. Solve is deterministic, so every
// repetition gives the same solution; only the time varies.
#pragma once

#include <vector>

#include "core/patch_scene.h"
#include "core/solve.h"
#include "core/solver_settings.h"

namespace radfarm::bench {

struct TimedSolve {
  SolveResult result;  // of the last repetition (all are identical)
  std::vector<double>
      seconds;  // wall time of each repetition: Solve() as called, BVH build included
  double median_seconds = 0;
};

TimedSolve RunTimedSolve(const PatchScene& scene, const SolverSettings& settings, int repetitions);

}  // namespace radfarm::bench
