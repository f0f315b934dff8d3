#include "core/display_budget.h"

#include <algorithm>

#include "core/direct_light.h"

namespace radfarm {

bool DisplayCastsRays(const PatchScene& scene, const SolverSettings& settings) {
  return DirectLightSections(scene, settings) > 0;
}

uint64_t DisplayRayAllowance(const SolverSettings& settings) {
  return BudgetShare(settings, kDisplayBudgetShare, kDisplayRaysPerSecond);
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
