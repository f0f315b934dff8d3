// The display a solve's settings ask for: with the direct light at its points where the solve
// starts from the direct light (core/direct_light.h), else the patches' averages. `radfarm render`
// and `radfarm fetch` both draw it so, from the same solution the same bits.
#pragma once

#include <vector>

#include "core/rgb.h"
#include "core/solver_settings.h"
#include "display/display_stage.h"
#include "mesh/patch_mesh.h"

namespace radfarm {

// `direct_light` is the direct light the solve started from (SolveResult::direct_light); empty
// where the solve had not started from it (a refining solve stopped before its restart point, or
// `radfarm fetch`, which has only the values): it is then the same pure function of the scene and
// `solver` again.
Display SolvedDisplay(const PatchMesh& mesh, const std::vector<Rgb>& radiosity,
                      const std::vector<Rgb>& direct_light, const SolverSettings& solver,
                      const DisplayProgress& progress = nullptr);

}  // namespace radfarm
