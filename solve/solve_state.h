// What a solve has done and where it stands at a round boundary: the state a checkpoint stores
// (`radfarm render --db`, the farm master's store) and a solve resumes from. One type for every
// driver of rounds (round_driver.h), so a state saved by one resumes in another.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/patch_scene.h"
#include "core/progressive_solver.h"
#include "core/rgb.h"
#include "core/solve_stats.h"

namespace radfarm {

struct SolveState {
  uint32_t round = 0;          // the plan's round number of the last round applied
  uint32_t rounds_done = 0;    // ProgressiveSolver::rounds_done()
  std::vector<Rgb> radiosity;  // per element of the mesh the state belongs to
  std::vector<Rgb> unshot;
  EnergyAccount energy;
  SolveTotals totals;     // spent up to and including that round
  uint32_t shooters = 0;  // of that round
  // The scene of the refined mesh, or null while the mesh is still the one the solve was given.
  // Borrowed: valid while the solve (or, on resume, the caller) keeps it.
  const PatchScene* refined_scene = nullptr;
  // Refinement steps that split, counted from the start of this solve (not of a resumed one): a
  // caller that stores the refined scene needs to encode it again only when this changes.
  uint32_t refinements = 0;
  uint32_t next_point = 0;  // refinement points passed (RefinementSchedule::next_point)
  // Set when the solve ends at this boundary, with the reason: a solve resumed from here runs no
  // round (a round capped by the ray budget may have left a few rays, which StopBeforeRound alone
  // would spend).
  std::optional<std::string> stop;
};

// After each round of a local solve, for progress displays.
struct RoundProgress {
  uint32_t round = 0;
  uint64_t rays = 0;  // total so far
  double seconds = 0;
  double unshot_fraction = 0;
  double tolerance = 0;
  const EnergyAccount* energy = nullptr;
  bool gather = false;            // the round was the final gather
  uint64_t gather_rays_left = 0;  // ProgressiveSolver::PendingGatherRays after the round
  // The round alone, for estimates (core/progress_estimator.h).
  uint64_t round_rays = 0;
  double round_seconds = 0;
  double unshot_before = 0;
  // Seconds per ray of the final gather over those of a shooting round, as measured on this
  // machine (RoundDriver::MeasureGatherRayCost); 0 when not measured.
  double gather_ray_cost = 0;
  // What the rounds' budgets (RoundDriver::budget) leave after the round; nullopt: no such budget.
  std::optional<uint64_t> budget_rays_left{};
  std::optional<double> budget_seconds_left{};
  // The display's rays expected after the solve (RoundDriver::display_rays_forecast).
  uint64_t display_rays = 0;
};

// While a round of a local solve runs (RefiningHooks::during_round), after each of its batches.
struct RoundRunning {
  uint32_t round = 0;
  uint64_t round_rays = 0;       // planned
  uint64_t round_rays_done = 0;  // computed so far
  double round_seconds = 0;      // since the round started
  bool gather = false;
  std::optional<double> budget_seconds_left{};  // as RoundProgress's, now
};

struct SolveResult {
  std::vector<Rgb> radiosity;  // per patch, MTL Ke units
  std::vector<Rgb> unshot;
  SolveStats stats;
  // The direct light per patch the solve started from (ProgressiveSolver::direct_light()); empty
  // where it did not. The display uses it (display/solved_display.h).
  std::vector<Rgb> direct_light;
  // The emitter patches' light is in direct_light (ProgressiveSolver::emitters_direct), and what
  // the punctual lamps delivered in it (ProgressiveSolver::punctual_power): a re-bake needs both.
  bool emitters_direct = false;
  double punctual_power = 0;
};

}  // namespace radfarm
