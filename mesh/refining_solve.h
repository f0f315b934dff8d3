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
//
// Hooks (`radfarm render --db`): after every round, the state to checkpoint, taken after the
// refinement step the round triggered, so that a solve resumed from it continues with the next
// round on the same mesh and the same points still to come; on resume, the refined mesh is rebuilt
// from its PatchScene (PatchMesh::Rebuilt on the mesh given, which gives the same patches).
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>

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

// The state of a refining solve at a round boundary.
struct RefiningCheckpoint {
  SolveCheckpoint solve;  // per element of the mesh below
  // The scene of the refined mesh, or null while the mesh is still the one given.
  const PatchScene* refined_scene = nullptr;
  // Steps that split, counted from the start of this call: a caller that stores the scene needs
  // to encode it again only when this changes.
  uint32_t refinements = 0;
  uint32_t next_point = 0;  // refinement points passed (RefinementSchedule::next_point)
  // Set when the solve stops after this round (StopAfterRound: a capped round), with the reason.
  std::optional<std::string> stop;
};

struct RefiningResume {
  const SolveCheckpoint* solve = nullptr;     // sizes: the elements of the mesh below
  const PatchScene* refined_scene = nullptr;  // null: the mesh given
  uint32_t next_point = 0;
  // The saved RefiningCheckpoint::stop: the solve ended there, no round is run.
  std::optional<std::string> stopped;
};

struct RefiningHooks {
  std::optional<RefiningResume> resume;
  std::function<void(const RefiningCheckpoint&)> after_round;  // on the calling thread
};

// Errors: refinement settings out of range (the message names the job file key); a resume state
// that does not fit the mesh (its scene does not rebuild, or the sizes differ).
Result<RefiningSolveResult> SolveRefining(
    PatchMesh mesh, const SolverSettings& settings, const RefineSettings& refine,
    const std::function<void(const RoundProgress&)>& on_round = {},
    const RefiningHooks& hooks = {});

}  // namespace radfarm
