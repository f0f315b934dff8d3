// A budget holds to the last output: under --rays or --seconds the display, the direct and
// gathered light at the display's own points (display/display_stage.h, after the solve, where
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
// the plan is the same on every machine; a fraction of what two cores of a desktop cast.
inline constexpr double kDisplayRaysPerSecond = 4e6;

// A time budget stops the rounds early enough for what follows them (AfterSolveSeconds): the
// display's rays, priced at kDisplayReserveRaysPerSecond, what two cores cast of them on a big
// scene, not at the allowance's cautious rate; and kAfterSolveSeconds plus
// kAfterSolveSecondsPerPatch a patch for the rest: the display's work at its points (the midpoint
// split, the contrast tests and cuts where the light bends, a capped light's kernel at each point)
// and the outputs (the image's strata, the PNG's deflate, the files). Fixed in the code, as
// kDisplayRaysPerSecond, from bench/budget on two cores: a slower machine runs over by the ratio.
// On fewer threads than that the display's rays and its work at its points take as much longer,
// and are priced so.
inline constexpr unsigned kAfterSolveThreads = 2;
inline constexpr double kDisplayReserveRaysPerSecond = 7e6;
inline constexpr double kAfterSolveSeconds = 0.3;
inline constexpr double kAfterSolveSecondsPerPatch = 16e-6;

// Whether a display with rays of its own follows the solve: it has a direct light to start from
// (DirectLightSections > 0); else the display averages the patches, for free.
bool DisplayCastsRays(const PatchScene& scene, const SolverSettings& settings);

// The rays the display may cast under the settings' budgets (0: no budget): max_rays and
// max_seconds x kDisplayRaysPerSecond, each over kDisplayBudgetShare, the smaller of the two.
uint64_t DisplayRayAllowance(const SolverSettings& settings);

// The seconds a time budget keeps for what follows the solve: the display's allowance at
// kDisplayReserveRaysPerSecond where a display with rays follows (DisplayCastsRays), and
// kAfterSolveSeconds + kAfterSolveSecondsPerPatch x the scene's patches; all but the fixed
// seconds times kAfterSolveThreads over the settings' threads where those are fewer.
double AfterSolveSeconds(const PatchScene& scene, const SolverSettings& settings);

// The budgets the solve's rounds stop at: max_rays less the display's share where a display with
// rays follows (DisplayCastsRays), max_seconds less AfterSolveSeconds. A time budget that leaves
// the rounds nothing stays a budget (kMinSolveSeconds): the solve is its start.
SolverSettings SolveBudget(const PatchScene& scene, const SolverSettings& settings);
inline constexpr double kMinSolveSeconds = 1e-3;

// The display's rays per shadow ray of the direct-light start, for a forecast made before the
// display is planned: both grow with the patches and the lights a point sees. Across the shipped
// scenes the ratio runs from about 2 (one lamp over large plain surfaces) to about 10 (a building
// of many lamps, where the display cuts most where the light bends); this is its median.
inline constexpr double kDisplayRaysPerStartRay = 6;

// The rays the display is expected to cast after the solve, for an ETA that includes it: none
// where it casts none (DisplayCastsRays), else kDisplayRaysPerStartRay x `start_rays` (the
// shadow rays of the solve's start on this mesh), at most DisplayRayAllowance under a budget.
uint64_t DisplayRaysForecast(const PatchScene& scene, const SolverSettings& settings,
                             uint64_t start_rays);

}  // namespace radfarm
