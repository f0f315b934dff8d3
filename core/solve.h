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
  bool gather = false;            // the round was the final gather
  uint64_t gather_rays_left = 0;  // ProgressiveSolver::PendingGatherRays after the round
};

struct SolveResult {
  std::vector<Rgb> radiosity;  // per patch, MTL Ke units
  std::vector<Rgb> unshot;
  SolveStats stats;
  // The direct light per patch the solve started from (ProgressiveSolver::direct_light()); empty
  // where it did not. The display uses it (PatchMesh::SetSolution).
  std::vector<Rgb> direct_light;
};

// Rays per batch in local solves. Any value gives the same result (see batch.h); this one keeps
// batches long enough to amortise scheduling and short enough to balance threads.
inline constexpr uint32_t kLocalBatchRays = 4096;

// Where an interrupted solve stands: the solver's state after a round and what it had spent, so
// that Solve continues exactly where it stopped (same later rounds, same bits).
struct SolveCheckpoint {
  uint32_t round = 0;        // the plan's round number of the last round applied
  uint32_t rounds_done = 0;  // ProgressiveSolver::rounds_done()
  std::vector<Rgb> radiosity;
  std::vector<Rgb> unshot;
  EnergyAccount energy;
  uint64_t rays = 0;  // spent up to and including that round
  uint64_t escaped_rays = 0;
  uint64_t backface_hits = 0;
  double seconds = 0;
  uint32_t shooters = 0;  // of that round
};

// Optional hooks around the rounds, for solves that keep their state in a store.
struct SolveHooks {
  // Start from here instead of from scratch; sizes must match the scene.
  const SolveCheckpoint* resume = nullptr;
  // After every round, on the calling thread: the state at that round boundary.
  std::function<void(const SolveCheckpoint&)> after_round;
};

// Runs rounds until the unshot fraction drops below settings.tolerance or a ray or time budget is
// spent. `on_round` (optional) is called after every round on the calling thread.
SolveResult Solve(const PatchScene& scene, const SolverSettings& settings,
                  const std::function<void(const RoundProgress&)>& on_round = {},
                  const SolveHooks& hooks = {});

}  // namespace radfarm
