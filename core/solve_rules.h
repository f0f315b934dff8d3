// The rules that decide, from a scene's size and the settings, whether a solve starts from the
// direct light and what display follows it, put in words for people: render prints them, stats.json
// carries them (`direct_start`, `display`) and the farm's status shows them, so a big job that gets
// less than a small one says so. The rules themselves are EmittersInDirectStart and
// DirectLightSections (core/direct_light.h) and DisplayCastsRays (core/display_budget.h).
#pragma once

#include <string>

#include "core/patch_scene.h"
#include "core/solver_settings.h"

namespace radfarm {

struct RuleOutcome {
  bool used = false;  // the start is from the direct light; the display lights its own points
  std::string why;    // one sentence, no trailing period, e.g. "not used: 412 lights ..."
};

// "from the direct light of ... at N x N points per patch" or "not used: <the rule and its
// figures>; the emitter patches shoot it instead".
RuleOutcome DirectStartRule(const PatchScene& scene, const SolverSettings& settings);

// "at its own points: ..." where the solve starts from the direct light (DisplayCastsRays), else
// "the patches' averages, no rays of its own: " and why the start was not used.
RuleOutcome DisplayRule(const PatchScene& scene, const SolverSettings& settings);

// The display where DisplayRule said points but its share of a budget did not cover one point's
// direct light (DisplayStats::averaged).
inline constexpr const char* kDisplayAveragedByBudget =
    "the patches' averages, no rays of its own: the budget's share for the display left no "
    "shadow rays for its points";

}  // namespace radfarm
