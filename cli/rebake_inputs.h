// `radfarm render --from DIR`: a re-bake of a changed scene from a previous render's solution
// (solve/previous_solve.h, the rebake.bin every render writes). Here the previous solution is
// read and matched to the changed scene's mesh, and each render's solution is kept for the next.
#pragma once

#include <string>

#include "base/result.h"
#include "core/direct_start.h"
#include "core/patch_scene.h"
#include "core/solver_settings.h"
#include "solve/previous_solve.h"
#include "solve/solve_state.h"

namespace radfarm {

// The scene's identities rebake.bin records: its meshing, and its meshing with its lamps.
struct SceneHashes {
  std::string geometry;  // the patches' shapes, surfaces and material ids
  std::string lamps;     // the same with the punctual lamps
};
SceneHashes HashesOf(const PatchScene& scene);

// DIR's rebake.bin, checked against `scene`, the changed scene meshed. Errors: DIR or its file
// missing or broken; a solution of other patches (another scene, or a change of geometry or of
// the mesh settings).
Result<PreviousSolve> LoadPreviousSolve(const std::string& dir, const PatchScene& scene,
                                        const SceneHashes& hashes);

// The re-bake's start (solve/previous_solve.h RebakeStart) where the punctual lamps are the
// previous render's; else empty: a lamp changed, and the solve traces its whole start again.
StartLightSource ReusedStart(const PreviousSolve& previous, const SolverSettings& settings,
                             const SceneHashes& hashes);

// What a re-bake of this render will need, for `scene`'s `solution`.
PreviousSolve PreviousSolveOf(const PatchScene& scene, const SolverSettings& settings,
                              const SolveResult& solution);

}  // namespace radfarm
