#include "core/solve_control.h"

#include <algorithm>
#include <cmath>

namespace radfarm {

std::optional<std::string> StopBeforeRound(const ProgressiveSolver& solver,
                                           const SolverSettings& settings, uint64_t rays,
                                           double seconds) {
  if (solver.UnshotFraction() <= settings.tolerance) {
    if (!solver.GatherPending()) return kStopConverged;
    // A gather needs its share of rays per gathering patch at least (PlanRound).
    if (settings.max_rays > 0 &&
        settings.max_rays - std::min(rays, settings.max_rays) < solver.MinGatherRays()) {
      return kStopRayBudget;
    }
  }
  if (settings.max_rays > 0 && rays >= settings.max_rays) return kStopRayBudget;
  if (settings.max_seconds > 0 && seconds >= settings.max_seconds) return kStopTimeBudget;
  return std::nullopt;
}

uint64_t NextRoundRayCap(const SolverSettings& settings, uint64_t rays) {
  return settings.max_rays > 0 ? settings.max_rays - rays : 0;
}

uint64_t TimeRayCap(const SolverSettings& settings, double seconds, double rays_per_second) {
  if (!(settings.max_seconds > 0) || !(rays_per_second > 0)) return 0;
  const double rays = (settings.max_seconds - seconds) * rays_per_second;
  return rays >= 1 ? static_cast<uint64_t>(std::min(rays, 1e18)) : 1;
}

uint64_t PacedRoundCap(uint64_t rays, double power, double unshot, double tolerance, double carry,
                       uint64_t left) {
  if (rays == 0 || left == 0 || !(power > 0) || !(unshot > tolerance)) return 0;
  // Every shot from now on: the unshot down to the tolerance, and what it carries back, again and
  // again (a geometric series), at this round's rays per unit of power.
  const double to_shoot = (unshot - tolerance) / (1 - std::clamp(carry, 0.0, 0.95));
  const double needed = double(rays) * std::max(to_shoot, power) / power;
  if (needed <= double(left)) return 0;
  const double cap = double(rays) * double(left) / needed;
  return static_cast<uint64_t>(std::clamp(cap, 1.0, double(rays)));
}

std::optional<std::string> StopAfterRound(const RoundPlan& plan, const ProgressiveSolver& solver,
                                          const SolverSettings& settings) {
  // A capped gather has converged but gathered with fewer rays than asked: the budget stopped it.
  if (plan.capped && (plan.gather || solver.UnshotFraction() > settings.tolerance)) {
    return kStopRayBudget;
  }
  return std::nullopt;
}

double ConvergenceFraction(double unshot_fraction, double tolerance) {
  if (unshot_fraction <= tolerance) return 1;
  if (unshot_fraction >= 1 || tolerance <= 0 || tolerance >= 1) return 0;
  return std::clamp(std::log(unshot_fraction) / std::log(tolerance), 0.0, 1.0);
}

}  // namespace radfarm
