// Adaptive refinement: one deterministic step from (mesh, solution, settings) to a finer mesh and
// the solution carried over to it. The round driver (solve/round_driver.h) calls it at fixed
// points, before the first round and after the round where the unshot fraction first falls below
// each of kRefinePoints, for `radfarm render` and the farm master alike: both get the same mesh.
//
// What splits (refine_criteria.h scores each element; a score above 1 splits it): elements where
// the Gouraud image would miss the light by more than the tolerance, i.e. where the light bends or
// breaks rather than varies linearly:
//   - the light still to arrive (shadow edges, penumbrae, contact shadows), judged with shadow
//     rays from a lattice over the element toward the strongest unshot patches; children are
//     judged again at once, down to the minimum size, since this needs no solution;
//   - once rounds have been applied, the element's radiance against its vertices' mean, when that
//     difference is above the tolerance and the ray noise (one level per step).
// Emitters never split (shooters stay coarse). Splitting halves every edge (element_split.h), so no
// edge falls below min_element_size; elements are split in decreasing score until the element
// budget would be exceeded.
//
// Transfer (CarryOver): each child inherits its parent's radiosity and unshot radiosity (radiance
// units, per area), so the unshot power of the parent is shared among its children in proportion to
// their areas, which sum to the parent's (to rounding). Emitters keep their patches, so the emitted
// power is unchanged bit for bit. Light already shot onto a split element cannot be redistributed
// among its children, though: they all keep the parent's average. So the first refinement after the
// direct light has been shot (a restart point) restarts the solution on the refined mesh instead
// (B = dB = emission, nothing absorbed or escaped yet; round numbers go on, so no ray repeats): it
// costs the rays of the direct light on the coarser mesh and lets the refinement see the real
// direct light, penumbrae and contact shadows included.
//
// Conformity: the new mesh is assembled like the first (PatchMesh::Rebuilt), so vertices are welded
// per surface and a coarse element's edge that carries a finer neighbour's corners gets them as
// T-vertices in its display triangles: the Gouraud image has no cracks, and vertex radiance is
// still averaged within a surface only, so creases stay sharp.
#pragma once

#include <cstdint>
#include <vector>

#include "base/result.h"
#include "core/progressive_solver.h"
#include "core/ray_caster.h"
#include "core/rgb.h"
#include "core/thread_pool.h"
#include "mesh/light_scores.h"
#include "mesh/patch_mesh.h"
#include "mesh/refine_settings.h"

namespace radfarm {

struct RefinePoint {
  double unshot_fraction;  // refine after the first round that leaves less than this unshot
  bool restart;            // restart the solution on the refined mesh (see above)
};
// The point follows the first round of most rooms (the lights shoot their power at once, a room
// with reflectance below 0.6 keeps less than 60% of it). There is no later point: a split without a
// restart leaves the children the parent's average of the light already shot, a blocky image that
// more elements do not improve.
inline constexpr RefinePoint kRefinePoints[] = {{0.6, true}};

// The refinement point a round that left `unshot_fraction` reaches: advances *next past every point
// the fraction has fallen below and returns the last of them, or null when it passed none.
const RefinePoint* PassedRefinePoint(double unshot_fraction, size_t* next);
// Defaults of RefineSettings' automatic values.
inline constexpr double kMinElementDivisions = 4;    // min_element_size = patch_size / 4
inline constexpr uint64_t kElementBudgetFactor = 8;  // max_elements = 8 x initial patches

// The automatic max_elements: kElementBudgetFactor x the initial patches, but no more elements than
// `memory_limit` bytes hold at EstimatedSolveBytes (mesh/memory_estimate.h; the mesh's
// PatchMesh::memory_limit(): --max-memory, or this machine's memory), so that a refined big job
// stops splitting rather than be killed by the kernel; never below the initial patches.
uint64_t AutomaticElementBudget(size_t initial_patches, uint64_t memory_limit);

// RefineSettings with its automatic values resolved for a mesh of `initial_patches` patches of
// size `patch_size`. Errors name the setting (the job file's key).
struct ResolvedRefineSettings {
  double tolerance = 0;
  double min_element_size = 0;
  uint64_t max_elements = 0;
};
Result<ResolvedRefineSettings> ResolveRefineSettings(const RefineSettings& settings,
                                                     double patch_size, size_t initial_patches,
                                                     double weld_tolerance, uint64_t memory_limit);

struct RefinedMesh {
  PatchMesh mesh;
  std::vector<Rgb> radiosity;
  std::vector<Rgb> unshot;
  std::vector<uint32_t> parent;  // per element: the element of the old mesh it lies in
  uint64_t split = 0;            // splits made (each adds three elements)
};

// One refinement step; its gradient test reads the solution at the vertices
// (mesh/vertex_averages.h). `ray_power` is emitted power / shot_rays of the rounds so far (0 before
// the first round). `caster` is a RayCaster of `mesh`'s scene. Evaluations run on `pool`, the
// light scores where `scores` traces them (light_scores.h; empty or nullopt: on `pool`); the
// result depends on neither.
RefinedMesh Refine(const PatchMesh& mesh, const std::vector<Rgb>& radiosity,
                   const std::vector<Rgb>& unshot, double ray_power,
                   const ResolvedRefineSettings& settings, const RayCaster& caster,
                   ThreadPool& pool, const LightScoreSource& scores = {});

// The solver state to Restore() on the refined mesh after a step that split something: the
// children's inherited values with the energy account's unshot power summed again over them, or,
// at a restart point, the initial state (B = dB = emission, only `emitted` kept).
struct CarriedState {
  std::vector<Rgb> radiosity;
  std::vector<Rgb> unshot;
  EnergyAccount energy;
  bool restart = false;  // the state is a fresh start: emission only
};
CarriedState CarryOver(RefinedMesh& refined, const EnergyAccount& energy, bool restart);

}  // namespace radfarm
