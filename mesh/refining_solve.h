// SolveRefining: Solve() (core/solve.h) with adaptive refinement (refine.h) at fixed points: before
// the first round, and after the first round that leaves the unshot fraction below each of
// kRefinePoints (unless that round ends the solve; the first point restarts the solution). Between
// those points the rounds are Solve()'s, planned, cast and applied by the same ProgressiveSolver
// steps; at a refinement the solver is rebuilt on the new mesh and Restore()d with the carried-over
// solution, the round count and the energy account (CarryOver, refine.h). Rays remain a pure
// function of (seed, round, shooter, k), so the result depends on the scene, settings and seed
// only, never on the thread count.
//
// With refinement disabled this is Solve() on the mesh as given, bit for bit.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>

#include "core/result.h"
#include "core/solve.h"
#include "mesh/patch_mesh.h"
#include "mesh/refine_settings.h"

namespace radfarm {

struct RefiningSolveResult {
  std::unique_ptr<PatchMesh> mesh;  // the mesh the solution belongs to
  SolveResult solution;
  uint64_t patches_before = 0;  // patches of the mesh given
  uint32_t refinements = 0;     // refinement steps that split at least one element
};

// Errors: refinement settings out of range (the message names the job file key).
Result<RefiningSolveResult> SolveRefining(
    PatchMesh mesh, const SolverSettings& settings, const RefineSettings& refine,
    const std::function<void(const RoundProgress&)>& on_round = {});

}  // namespace radfarm
