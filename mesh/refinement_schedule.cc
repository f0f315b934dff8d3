#include "mesh/refinement_schedule.h"

#include <iterator>
#include <string>
#include <utility>

namespace radfarm {

Result<RefinementSchedule> RefinementSchedule::Create(const RefineSettings& settings,
                                                      const PatchMesh& initial, uint64_t shot_rays,
                                                      size_t next_point) {
  if (next_point > std::size(kRefinePoints)) {
    return Error{"refinement point " + std::to_string(next_point) + " out of range (there are " +
                 std::to_string(std::size(kRefinePoints)) + ")"};
  }
  Result<ResolvedRefineSettings> resolved =
      ResolveRefineSettings(settings, initial.patch_size(), initial.patch_scene().patches.size(),
                            initial.weld_tolerance());
  if (!resolved.ok()) return Error{resolved.error()};
  return RefinementSchedule(*resolved, shot_rays, next_point);
}

std::optional<RefinementStep> RefinementSchedule::BeforeFirstRound(PatchMesh& mesh,
                                                                   const ProgressiveSolver& solver,
                                                                   const RayCaster& caster,
                                                                   ThreadPool& pool) const {
  return Step(mesh, solver, 0, false, caster, pool);
}

bool RefinementSchedule::PointPassed(const ProgressiveSolver& solver) const {
  size_t next = next_point_;
  return PassedRefinePoint(solver.UnshotFraction(), &next) != nullptr;
}

std::optional<RefinementStep> RefinementSchedule::AfterRound(PatchMesh& mesh,
                                                             const ProgressiveSolver& solver,
                                                             const RayCaster& caster,
                                                             ThreadPool& pool) {
  const RefinePoint* point = PassedRefinePoint(solver.UnshotFraction(), &next_point_);
  if (point == nullptr) return std::nullopt;
  const double ray_power =
      RayPower(solver.energy().emitted, shot_rays_, mesh.patch_scene().patches.size());
  return Step(mesh, solver, ray_power, point->restart, caster, pool);
}

std::optional<RefinementStep> RefinementSchedule::Step(PatchMesh& mesh,
                                                       const ProgressiveSolver& solver,
                                                       double ray_power, bool restart,
                                                       const RayCaster& caster,
                                                       ThreadPool& pool) const {
  RefinedMesh refined =
      Refine(mesh, solver.radiosity(), solver.unshot(), ray_power, settings_, caster, pool);
  if (refined.split == 0) return std::nullopt;
  CarriedState carried = CarryOver(refined, solver.energy(), restart);
  return RefinementStep{std::move(refined.mesh), std::move(carried), solver.rounds_done()};
}

}  // namespace radfarm
