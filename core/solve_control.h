// The stopping rules of a solve, applied by the round driver (solve/round_driver.h) for `radfarm
// render` and the farm master alike, so that both stop after the same round and report the same
// reason: converged (unshot fraction at or below the tolerance, or nothing left to shoot), the ray
// budget (max_rays; the last round is trimmed to it) or the time budget (max_seconds).
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "core/progressive_solver.h"
#include "core/solver_settings.h"

namespace radfarm {

inline constexpr const char* kStopConverged = "converged";
inline constexpr const char* kStopRayBudget = "ray budget";
inline constexpr const char* kStopTimeBudget = "time budget";

// Why the solve stops before planning another round, or nullopt to plan one. `rays` and `seconds`
// are what the solve has spent so far.
std::optional<std::string> StopBeforeRound(const ProgressiveSolver& solver,
                                           const SolverSettings& settings, uint64_t rays,
                                           double seconds);

// The ray cap for the next round's PlanRound (0: none).
uint64_t NextRoundRayCap(const SolverSettings& settings, uint64_t rays);

// The ray cap that keeps the next round within the time budget at `rays_per_second`, after
// `seconds` spent (at least 1; 0: no time budget or no estimate).
uint64_t TimeRayCap(const SolverSettings& settings, double seconds, double rays_per_second);

// Paces the shooting rounds to a budget, so that the solve spends it converging rather than on
// its first rounds alone: the cap for the next shooting round where the rounds still to come would
// not fit in the `left` rays the budget has, else 0 (no cap from pacing). The round shoots `power`
// with `rays` (PlanRound's rays are in proportion to the power shot); the rounds after it shoot
// what each before carried back (a `carry` share of it, ProgressiveSolver::EstimatedCarry), until
// the `unshot` (a fraction of the emitted power, as `power`) is down to the `tolerance`. The cap
// is this round's share of `left`: every round then casts the same fraction of the rays it would
// without a budget, and noisier rounds that converge beat full ones that stop with the light
// unshot. A cap is never below one ray a shot, nor above what the round plans anyway.
uint64_t PacedRoundCap(uint64_t rays, double power, double unshot, double tolerance, double carry,
                       uint64_t left);

// After ApplyRound of `plan`: a capped round that left the solve unconverged spent the budget.
std::optional<std::string> StopAfterRound(const RoundPlan& plan, const ProgressiveSolver& solver,
                                          const SolverSettings& settings);

// Fraction of the way to convergence: unshot power falls geometrically, so progress is measured in
// log space from 1 (start) to the tolerance (done).
double ConvergenceFraction(double unshot_fraction, double tolerance);

}  // namespace radfarm
