#include "mesh/refinement_schedule.h"

#include <algorithm>
#include <iterator>
#include <string>
#include <utility>

#include "base/result.h"

namespace radfarm {

void RestoreStep(RefinementStep& step, ProgressiveSolver& solver) {
  if (step.state.restart && !solver.direct_light().empty()) {
    solver.Restore(step.rounds_done, solver.radiosity(), solver.unshot(), solver.energy());
    return;
  }
  solver.Restore(step.rounds_done, std::move(step.state.radiosity), std::move(step.state.unshot),
                 step.state.energy);
}

Result<RefinementSchedule> RefinementSchedule::Create(const RefineSettings& settings,
                                                      const PatchMesh& initial, uint64_t shot_rays,
                                                      size_t next_point) {
  if (next_point > std::size(kRefinePoints)) {
    return Error{"refinement point " + std::to_string(next_point) + " out of range (there are " +
                 std::to_string(std::size(kRefinePoints)) + ")"};
  }
  Result<ResolvedRefineSettings> resolved =
      ResolveRefineSettings(settings, initial.patch_size(), initial.patch_scene().patches.size(),
                            initial.weld_tolerance(), initial.memory_limit());
  RADFARM_RETURN_IF_ERROR(resolved);
  return RefinementSchedule(*resolved, shot_rays, next_point);
}

std::optional<RefinementStep> RefinementSchedule::BeforeFirstRound(
    PatchMesh& mesh, const ProgressiveSolver& solver, const RayCaster& caster, ThreadPool& pool,
    const LightScoreSource& scores) const {
  return Step(mesh, solver, 0, false, caster, pool, scores);
}

bool RefinementSchedule::BeforeRestart() const {
  for (size_t p = next_point_; p < std::size(kRefinePoints); ++p) {
    if (kRefinePoints[p].restart) return true;
  }
  return false;
}

SolverSettings RefinementSchedule::SolverSettingsNow(const SolverSettings& settings,
                                                     size_t patches) const {
  SolverSettings now = settings;
  if (BeforeRestart()) {
    // Refinement finds shadows from the light the emitters shoot (StrongestSources), which the
    // final gather's direct-light start does not shoot.
    // The divisor applies to a shooting solve's rays (`now`, gather off), not a gathering one's.
    now.gather_rays = 0;
    now.shot_rays = std::max<uint64_t>(1, ResolvedShotRays(now, patches) / kPreRestartRayDivisor);
  }
  return now;
}

bool RefinementSchedule::PointPassed(const ProgressiveSolver& solver) const {
  size_t next = next_point_;
  return PassedRefinePoint(solver.UnshotFraction(), &next) != nullptr;
}

std::optional<RefinementStep> RefinementSchedule::AfterRound(PatchMesh& mesh,
                                                             const ProgressiveSolver& solver,
                                                             const RayCaster& caster,
                                                             ThreadPool& pool,
                                                             const LightScoreSource& scores) {
  // The power each ray of the rounds so far carried, before the point passed changes the phase.
  SolverSettings used;
  used.shot_rays = shot_rays_;
  used = SolverSettingsNow(used, mesh.patch_scene().patches.size());
  const double ray_power =
      solver.energy().emitted / double(ResolvedShotRays(used, mesh.patch_scene().patches.size()));
  const RefinePoint* point = PassedRefinePoint(solver.UnshotFraction(), &next_point_);
  if (point == nullptr) return std::nullopt;
  return Step(mesh, solver, ray_power, point->restart, caster, pool, scores);
}

std::optional<RefinementStep> RefinementSchedule::Step(PatchMesh& mesh,
                                                       const ProgressiveSolver& solver,
                                                       double ray_power, bool restart,
                                                       const RayCaster& caster, ThreadPool& pool,
                                                       const LightScoreSource& scores) const {
  RefinedMesh refined =
      Refine(mesh, solver.radiosity(), solver.unshot(), ray_power, settings_, caster, pool, scores);
  // A restart point restarts even when nothing split: the rounds before it had fewer rays.
  if (refined.split == 0 && !restart) return std::nullopt;
  CarriedState carried = CarryOver(refined, solver.energy(), restart);
  return RefinementStep{std::move(refined.mesh), std::move(carried), solver.rounds_done()};
}

}  // namespace radfarm
