// A budget holds to the last output (issue 21): under --rays or --seconds the display, the direct
// and gathered light at the display's own points (PatchMesh::SetSolution, after the solve, where
// the outputs are written: `radfarm render` and `radfarm fetch`), gets a share of the budget, and
// the solve keeps the rest. The display's plan is a pure function of the job's settings and the
// mesh, so that `render` and `fetch` draw the same display from the same solution.
#pragma once

#include <cstdint>

#include "core/patch_scene.h"
#include "core/solver_settings.h"

namespace radfarm {

// The display spends at most this share of a budget: a quarter of max_rays, and of max_seconds a
// quarter at kDisplayRaysPerSecond.
inline constexpr uint64_t kDisplayBudgetShare = 4;
// The rate a time budget's display is planned at, in its rays (shadow rays and gathering rays
// with their second bounces): fixed in the code, as the start's (kStartShadowRaysPerSecond), so
// the plan is the same on every machine; about a third of what two cores of a 2020s desktop cast.
inline constexpr double kDisplayRaysPerSecond = 4e6;

// Whether a display with rays of its own follows the solve: it has a direct light to start from
// (DirectLightSections > 0); else the display averages the patches, for free.
bool DisplayCastsRays(const PatchScene& scene, const SolverSettings& settings);

// The rays the display may cast under the settings' budgets (0: no budget): max_rays and
// max_seconds x kDisplayRaysPerSecond, each over kDisplayBudgetShare, the smaller of the two.
uint64_t DisplayRayAllowance(const SolverSettings& settings);

// The budgets the solve's rounds stop at: the settings' less the display's share where a display
// with rays follows (DisplayCastsRays), else the settings' own.
SolverSettings SolveBudget(const PatchScene& scene, const SolverSettings& settings);

}  // namespace radfarm
