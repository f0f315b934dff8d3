#include "core/display_budget.h"

#include <algorithm>

#include "core/direct_light.h"

namespace radfarm {

bool DisplayCastsRays(const PatchScene& scene, const SolverSettings& settings) {
  return DirectLightSections(scene, settings) > 0;
}

uint64_t DisplayRayAllowance(const SolverSettings& settings) {
  uint64_t allowance = 0;
  if (settings.max_rays > 0)
    allowance = std::max<uint64_t>(1, settings.max_rays / kDisplayBudgetShare);
  if (settings.max_seconds > 0) {
    const double rays = settings.max_seconds * kDisplayRaysPerSecond / kDisplayBudgetShare;
    const uint64_t by_time = static_cast<uint64_t>(std::clamp(rays, 1.0, 1e18));
    allowance = allowance > 0 ? std::min(allowance, by_time) : by_time;
  }
  return allowance;
}

SolverSettings SolveBudget(const PatchScene& scene, const SolverSettings& settings) {
  SolverSettings budget = settings;
  if ((settings.max_rays == 0 && !(settings.max_seconds > 0)) ||
      !DisplayCastsRays(scene, settings)) {
    return budget;
  }
  if (settings.max_rays > 0) {
    budget.max_rays =
        std::max<uint64_t>(1, settings.max_rays - settings.max_rays / kDisplayBudgetShare);
  }
  if (settings.max_seconds > 0) {
    budget.max_seconds = settings.max_seconds * (1 - 1.0 / kDisplayBudgetShare);
  }
  return budget;
}

}  // namespace radfarm
