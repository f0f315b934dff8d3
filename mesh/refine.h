// Adaptive refinement: one deterministic step from (mesh, solution, settings) to a finer mesh and
// the solution carried over to it. The solve (refining_solve.h) calls it at fixed points, before
// the first round and after the rounds where the unshot fraction first falls below each of
// kRefineAtUnshotFraction; the farm master can call it at the same points and get the same mesh.
//
// What splits (refine_criteria.h scores each element; a score above 1 splits it):
//   - elements across which the light still to arrive varies (shadow edges, penumbrae, fall-off
//     near a light), judged with shadow rays toward the strongest unshot patches; children are
//     judged again at once, down to the minimum size, since this needs no solution;
//   - once rounds have been applied, elements whose radiance differs from their vertices' by more
//     than the tolerance and more than the ray noise (one level per step).
// Emitters never split (shooters stay coarse). Splitting halves every edge (element_split.h), so no
// edge falls below min_element_size; elements are split in decreasing score until the element
// budget would be exceeded.
//
// Transfer: each child inherits its parent's radiosity and unshot radiosity (radiance units, per
// area), so the unshot power of the parent is shared among its children in proportion to their
// areas, which sum to the parent's (to rounding). Emitters keep their patches, so the emitted power
// is unchanged bit for bit.
//
// Conformity: the new mesh is assembled like the first (PatchMesh::Rebuilt), so vertices are welded
// per surface and a coarse element's edge that carries a finer neighbour's corners gets them as
// T-vertices in its display triangles: the Gouraud image has no cracks, and vertex radiance is
// still averaged within a surface only, so creases stay sharp.
#pragma once

#include <cstdint>
#include <vector>

#include "core/ray_caster.h"
#include "core/result.h"
#include "core/rgb.h"
#include "core/thread_pool.h"
#include "mesh/patch_mesh.h"
#include "mesh/refine_settings.h"

namespace radfarm {

inline constexpr double kRefineAtUnshotFraction[] = {0.3, 0.05};
// Defaults of RefineSettings' automatic values.
inline constexpr double kMinElementDivisions = 8;    // min_element_size = patch_size / 8
inline constexpr uint64_t kElementBudgetFactor = 8;  // max_elements = 8 x initial patches

// RefineSettings with its automatic values resolved for a mesh of `initial_patches` patches of
// size `patch_size`. Errors name the setting (the job file's key).
struct ResolvedRefineSettings {
  double tolerance = 0;
  double min_element_size = 0;
  uint64_t max_elements = 0;
};
Result<ResolvedRefineSettings> ResolveRefineSettings(const RefineSettings& settings,
                                                     double patch_size, size_t initial_patches,
                                                     double weld_tolerance);

struct RefinedMesh {
  PatchMesh mesh;
  std::vector<Rgb> radiosity;
  std::vector<Rgb> unshot;
  std::vector<uint32_t> parent;  // per element: the element of the old mesh it lies in
  uint64_t split = 0;            // splits made (each adds three elements)
};

// One refinement step. `mesh` receives the solution (SetSolution) for its vertex radiance.
// `ray_power` is emitted power / shot_rays of the rounds so far (0 before the first round).
// `caster` is a RayCaster of `mesh`'s scene. Evaluations run on `pool`; the
// result does not depend on its size.
RefinedMesh Refine(PatchMesh& mesh, const std::vector<Rgb>& radiosity,
                   const std::vector<Rgb>& unshot, double ray_power,
                   const ResolvedRefineSettings& settings, const RayCaster& caster,
                   ThreadPool& pool);

}  // namespace radfarm
