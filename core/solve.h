// Solve: a whole progressive-refinement solution on this machine, rounds run on a thread pool.
#pragma once

#include <functional>
#include <vector>

#include "core/patch_scene.h"
#include "core/progressive_solver.h"
#include "core/rgb.h"
#include "core/solve_stats.h"
#include "core/solver_settings.h"

namespace radfarm {

struct RoundProgress {
  uint32_t round = 0;
  uint64_t rays = 0;  // total so far
  double seconds = 0;
  double unshot_fraction = 0;
  double tolerance = 0;
  const EnergyAccount* energy = nullptr;
};

struct SolveResult {
  std::vector<Rgb> radiosity;  // per patch, MTL Ke units
  std::vector<Rgb> unshot;
  SolveStats stats;
};

// Rays per batch in local solves. Any value gives the same result (see batch.h); this one keeps
// batches long enough to amortise scheduling and short enough to balance threads.
inline constexpr uint32_t kLocalBatchRays = 4096;

// Runs rounds until the unshot fraction drops below settings.tolerance or a ray or time budget is
// spent. `on_round` (optional) is called after every round on the calling thread.
SolveResult Solve(const PatchScene& scene, const SolverSettings& settings,
                  const std::function<void(const RoundProgress&)>& on_round = {});

}  // namespace radfarm
