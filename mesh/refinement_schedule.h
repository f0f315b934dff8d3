// RefinementSchedule: when a refining solve refines its mesh and with which arguments. The round
// driver (solve/round_driver.h) follows it for `radfarm render` and the farm master alike, so both
// call Refine (refine.h) at the same rounds with the same inputs and get the same mesh to the bit.
//
// A solve drives it between its rounds:
//   BeforeFirstRound    once, before planning round 0 (light criterion only, ray power 0);
//   AfterRound          after every ApplyRound whose round did not end the solve (StopAfterRound
//                       found nothing): refines when the round passed a point of kRefinePoints.
// A step that split something returns the new mesh and the solver state to Restore() on it with
// `rounds_done` (the round count goes on, so no ray repeats). The caller replaces its mesh, scene
// and solver; the schedule only remembers how many points have passed (`next_point`), which a
// checkpoint must keep: a resumed solve that forgot it would refine again at a point already
// passed.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>

#include "base/result.h"
#include "core/progressive_solver.h"
#include "core/ray_caster.h"
#include "core/solver_settings.h"
#include "core/thread_pool.h"
#include "mesh/patch_mesh.h"
#include "mesh/refine.h"
#include "mesh/refine_settings.h"

namespace radfarm {

// Rounds before a restart point cast this fraction of the rays.
inline constexpr uint64_t kPreRestartRayDivisor = 4;

// The outcome of a refinement step that split at least one element, or of a restart point (which
// restarts the solution on the same mesh when nothing split).
struct RefinementStep {
  PatchMesh mesh;            // the refined mesh
  CarriedState state;        // to Restore() on a solver of mesh.patch_scene()
  uint32_t rounds_done = 0;  // ... with this round count (the old solver's)
};

// Puts a step's carried state into `solver`, built for step.mesh with SolverSettingsNow. A restart
// keeps the fresh start the solver was built with when that is the direct light (the final
// gather), with the step's round count; any other state is Restore()d as carried.
void RestoreStep(RefinementStep& step, ProgressiveSolver& solver);

class RefinementSchedule {
 public:
  // Resolves `settings` for `initial`, the mesh PatchMesh::Build made (errors name the job file's
  // key). `shot_rays` is the solver's setting (0: automatic), for the ray power. `next_point`: the
  // refinement points already passed (0 for a fresh solve, a checkpoint's value on resume).
  static Result<RefinementSchedule> Create(const RefineSettings& settings, const PatchMesh& initial,
                                           uint64_t shot_rays, size_t next_point = 0);

  // Before round 0. `mesh` and `solver` are the solve's (solver on mesh.patch_scene(), nothing
  // applied yet); `caster` traces mesh.patch_scene(). Refine stores the solution in `mesh`. The
  // light scores are traced where `scores` says (mesh/light_scores.h; empty: on `pool`).
  std::optional<RefinementStep> BeforeFirstRound(PatchMesh& mesh, const ProgressiveSolver& solver,
                                                 const RayCaster& caster, ThreadPool& pool,
                                                 const LightScoreSource& scores = {}) const;

  // Whether the round just applied passes a refinement point, without advancing: callers that
  // build the caster only when needed ask this first.
  bool PointPassed(const ProgressiveSolver& solver) const;

  // After a round that did not end the solve: advances past the points the unshot fraction has
  // fallen below and, if it passed any, refines at the last of them.
  std::optional<RefinementStep> AfterRound(PatchMesh& mesh, const ProgressiveSolver& solver,
                                           const RayCaster& caster, ThreadPool& pool,
                                           const LightScoreSource& scores = {});

  // The settings of the solver for the rounds up to the next refinement point, on a mesh of
  // `patches` elements: before a restart point the shot rays are divided by
  // kPreRestartRayDivisor, since the restart discards those rounds' light and they only have to
  // show where the light bends (the Gradient score's noise gate allows for their fewer rays).
  // Every solver of a refining solve (SolveRefining, the farm master, a resume) is built with
  // these. Before the restart point the final gather is off (gather_rays = 0): refinement finds
  // shadows from the light the emitters shoot, which the gather's direct-light start does not
  // shoot. From the restart on (the last point) the solve gathers as the settings say.
  SolverSettings SolverSettingsNow(const SolverSettings& settings, size_t patches) const;

  size_t next_point() const { return next_point_; }
  const ResolvedRefineSettings& settings() const { return settings_; }

 private:
  bool BeforeRestart() const;
  RefinementSchedule(const ResolvedRefineSettings& settings, uint64_t shot_rays, size_t next_point)
      : settings_(settings), shot_rays_(shot_rays), next_point_(next_point) {}
  std::optional<RefinementStep> Step(PatchMesh& mesh, const ProgressiveSolver& solver,
                                     double ray_power, bool restart, const RayCaster& caster,
                                     ThreadPool& pool, const LightScoreSource& scores) const;

  ResolvedRefineSettings settings_;
  uint64_t shot_rays_ = 0;
  size_t next_point_ = 0;
};

}  // namespace radfarm
