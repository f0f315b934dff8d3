#include "core/display_budget.h"

#include <algorithm>
#include <thread>

#include "core/direct_light.h"

namespace radfarm {

bool DisplayCastsRays(const PatchScene& scene, const SolverSettings& settings) {
  return DirectLightSections(scene, settings) > 0;
}

uint64_t DisplayRayAllowance(const SolverSettings& settings) {
  return BudgetShare(settings, kDisplayBudgetShare, kDisplayRaysPerSecond);
}

uint64_t DisplayRaysForecast(const PatchScene& scene, const SolverSettings& settings,
                             uint64_t start_rays) {
  if (start_rays == 0 || !DisplayCastsRays(scene, settings)) return 0;
  const uint64_t forecast = uint64_t(kDisplayRaysPerStartRay * double(start_rays));
  const uint64_t allowance = DisplayRayAllowance(settings);
  return allowance > 0 ? std::min(forecast, allowance) : forecast;
}

namespace {

// AfterSolveSeconds with DisplayCastsRays known (it plans the start: asked once a budget).
double AfterSolveSeconds(const PatchScene& scene, const SolverSettings& settings,
                         bool display_rays) {
  const double rays = display_rays ? double(DisplayRayAllowance(settings)) : 0.0;
  const unsigned threads =
      settings.threads != 0 ? settings.threads : std::max(1u, std::thread::hardware_concurrency());
  const double slower = double(kAfterSolveThreads) / std::min(threads, kAfterSolveThreads);
  return kAfterSolveSeconds + slower * (rays / kDisplayReserveRaysPerSecond +
                                        kAfterSolveSecondsPerPatch * double(scene.patches.size()));
}

}  // namespace

double AfterSolveSeconds(const PatchScene& scene, const SolverSettings& settings) {
  return AfterSolveSeconds(scene, settings, DisplayCastsRays(scene, settings));
}

SolverSettings SolveBudget(const PatchScene& scene, const SolverSettings& settings) {
  SolverSettings budget = settings;
  if (settings.max_rays == 0 && !(settings.max_seconds > 0)) return budget;
  const bool display_rays = DisplayCastsRays(scene, settings);
  if (settings.max_rays > 0 && display_rays) {
    budget.max_rays =
        std::max<uint64_t>(1, settings.max_rays - settings.max_rays / kDisplayBudgetShare);
  }
  if (settings.max_seconds > 0) {
    budget.max_seconds = std::max(
        kMinSolveSeconds, settings.max_seconds - AfterSolveSeconds(scene, settings, display_rays));
  }
  return budget;
}

}  // namespace radfarm
