// Section 1 of the report: speed against error. Every sampler is run over a ladder of ray budgets
// on one scene, each run timed (median of repetitions) and scored against a high-ray reference
// solution computed once, in the same process, with a different seed (a reference sharing the runs'
// seed would share their first rays and flatter their error).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "bench/bench_scene.h"
#include "bench/patch_error.h"
#include "bench/timed_solve.h"
#include "core/rgb.h"
#include "core/solver_settings.h"

namespace radfarm::bench {

struct SweepConfig {
  // Ladder of SolverSettings::shot_rays for the random and Sobol samplers.
  std::vector<uint64_t> shot_rays;
  // The grid's line: this step, this many shooters per round, and as max_rays the ray count the
  // Sobol run at the same rung used (the grid fixes its rays per shot, so shot_rays does not
  // apply).
  double grid_step_degrees = 4;
  uint32_t grid_shooters_per_round = 16;
  // The grid at the top rung's ray budget with each of these steps.
  std::vector<double> grid_steps;
  // The grid with each of these steps, run to the tolerance without a ray budget: where its
  // (biased) answer ends up, and how long it takes to get there.
  std::vector<double> grid_converged_steps;
  int repetitions = 3;
  double tolerance = 1e-3;
  uint64_t seed = 1;
  // Reference: Sobol, shot_rays = reference_factor * the largest rung, tighter tolerance, own seed.
  uint64_t reference_factor = 64;
  double reference_tolerance = 1e-5;
  uint64_t reference_seed = 1000003;
};

// One timed, scored solve.
struct SweepPoint {
  SolverSettings settings;
  std::string budget;  // the knob that was turned, for the table
  uint64_t rays = 0;
  uint64_t rounds = 0;
  double seconds = 0;  // median wall time of Solve()
  double rays_per_second = 0;
  double error = 0;      // RmsRelativeError against the reference, over all patches with Bref > 0
  double error_lit = 0;  // the same over the lit patches (patch_error.h)
  double unshot_fraction = 0;
  std::string stop_reason;
};

struct Reference {
  SolverSettings settings;
  uint64_t rays = 0;
  uint64_t rounds = 0;
  double seconds = 0;
  std::vector<Rgb> radiosity;
  ErrorPatches patches;  // which patches the two error measures average over
};

struct SceneSweep {
  std::string scene;
  std::string path;
  size_t patches = 0;
  double patch_size = 0;
  double load_seconds = 0;
  Reference reference;
  std::vector<SweepPoint> points;          // the lines: every sampler over the ladder
  std::vector<SweepPoint> grid_steps;      // the grid's step at the top rung's ray budget
  std::vector<SweepPoint> grid_converged;  // the grid run to the tolerance
};

Reference ComputeReference(const BenchScene& scene, const SweepConfig& config);

// Scores a timed solve against `reference`.
SweepPoint ScorePoint(const TimedSolve& timed, const SolverSettings& settings, std::string budget,
                      const Reference& reference);

// Times and scores one setting against `reference`.
SweepPoint RunPoint(const BenchScene& scene, const SolverSettings& settings, std::string budget,
                    const Reference& reference, int repetitions);

SceneSweep RunSweep(const BenchScene& scene, const SweepConfig& config);

// One line of progress on stdout.
void PrintPoint(const std::string& scene, const SweepPoint& point);

}  // namespace radfarm::bench
