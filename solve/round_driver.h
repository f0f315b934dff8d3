// RoundDriver: the one loop of a radiosity solve, as a state machine that does not cast rays
// itself. `radfarm render` runs it on its thread pool (local_solve.h); the farm master runs it
// through its scheduler, with agents computing the batches (daemon/jobs/running_job.h). Both
// therefore plan, apply, stop and refine at the same rounds with the same inputs, and get the same
// bits.
//
//   Start       build the solver on the mesh (the direct light of a gathering solve), or rebuild a
//               checkpoint's state on it; refine before round 0 when refinement is on
//   PlanNext    the stopping rules (core/solve_control.h), then the next round's plan, or nullopt
//               once the solve stops (stop_reason() says why)
//   [the plan's batches computed anywhere, in any order: core/batch.h]
//   Apply       the round's results folded in; the stop a capped round makes; a refinement step
//               (mesh/refinement_schedule.h) when the round passed a refinement point and the
//               solve goes on: the mesh, scene and solver are then new (mesh_generation() moves)
//   State       the state at this boundary, for a checkpoint (solve_state.h)
//   Finish      the solution and its stats
//
// The driver owns the mesh, the solver and the schedule. It builds a ray caster only when asked
// (caster()) or when a refinement step needs one, and keeps it until the mesh changes.
// Threads: one caller at a time; the thread pool given to Start is used for refinement steps.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "base/result.h"
#include "core/batch.h"
#include "core/direct_start.h"
#include "core/patch_scene.h"
#include "core/progressive_solver.h"
#include "core/ray_caster.h"
#include "core/ray_cost_probe.h"
#include "core/round_reduction.h"
#include "core/solver_settings.h"
#include "core/thread_pool.h"
#include "core/warm_start.h"
#include "mesh/light_scores.h"
#include "mesh/patch_mesh.h"
#include "mesh/refine_settings.h"
#include "mesh/refinement_schedule.h"
#include "solve/solve_state.h"

namespace radfarm {

// What Apply did: the round's own figures, taken before any refinement step it triggered.
struct AppliedRound {
  uint64_t escaped_rays = 0;
  uint64_t back_rays = 0;
  double unshot_fraction = 0;
  double unshot_power = 0;  // EnergyAccount::unshot
  uint64_t gather_rays_left = 0;
  bool refined = false;       // a refinement step replaced the mesh, scene and solver
  double refine_seconds = 0;  // spent deciding on and making that step
};

class RoundDriver {
 public:
  // A solve of `mesh` (refined as `refine` says), resumed from `resume` if given (its radiosity
  // per element of the refined scene it names, or of `mesh`). `pool` serves refinement steps and
  // must outlive the driver. Errors: refinement settings out of range (naming the job file key); a
  // resume state that does not fit the mesh.
  // `start`, if given, traces every solver's direct-light start, the one a refinement restart
  // makes included (core/direct_start.h); without, the solver traces it on settings.threads.
  // `scores`, if given, traces every refinement step's light scores (mesh/light_scores.h);
  // without, they are traced on `pool`.
  static Result<std::unique_ptr<RoundDriver>> Start(PatchMesh mesh, const SolverSettings& settings,
                                                    const RefineSettings& refine,
                                                    const SolveState* resume, ThreadPool& pool,
                                                    StartLightSource start = {},
                                                    LightScoreSource scores = {});
  // A solve of a bare scene, never refined; `scene` must outlive the driver.
  static std::unique_ptr<RoundDriver> Start(const PatchScene& scene, const SolverSettings& settings,
                                            const SolveState* resume);
  // A solve of `scene`, which the driver keeps, never refined: for a caller that needs no mesh
  // (the farm master without refinement, which need not hold the OpenMesh mesh, about 300 bytes a
  // patch, while it solves). Errors: a resume state that does not fit the scene.
  static Result<std::unique_ptr<RoundDriver>> StartOwning(PatchScene scene,
                                                          const SolverSettings& settings,
                                                          const SolveState* resume,
                                                          StartLightSource start = {});
  ~RoundDriver();
  RoundDriver(const RoundDriver&) = delete;
  RoundDriver& operator=(const RoundDriver&) = delete;

  // The next round, its batches of at most `batch_rays` rays, after `seconds` spent in all; or
  // nullopt when the solve stops before it. With a time budget and `rays_per_second` (the
  // caller's estimate of its pace; 0: none), the round is trimmed to the rays that fit in the
  // seconds left, so a long first round cannot overrun the budget; such a round ends the solve
  // ("time budget"), as a trimmed round of a ray budget does.
  std::optional<RoundPlan> PlanNext(uint32_t batch_rays, double seconds,
                                    double rays_per_second = 0);
  // Folds in `plan`'s results (`results[k]` of plan.batches[k]), `seconds` spent in all by now.
  AppliedRound Apply(const RoundPlan& plan, const std::vector<BatchResult>& results,
                     double seconds);
  // Apply with the results folded in as they arrive, so a round's results are never all held
  // (core/round_reduction.h): Reduction(plan), Add every batch's result to it, then
  // Apply(plan, reduction, seconds). The same bits as the Apply above. Between Reduction and
  // Apply nothing else may be called on the driver.
  std::unique_ptr<RoundReduction> Reduction(const RoundPlan& plan);
  AppliedRound Apply(const RoundPlan& plan, RoundReduction& reduction, double seconds);

  // A re-bake: before the first round, the solver starts from `previous`, a converged solution of
  // the same patches with other emission and reflectance (core/warm_start.h), and shoots the
  // difference; no final gather. Errors: sizes that do not fit the scene; a patch that was black
  // and now reflects.
  Status WarmStart(const PreviousPatchValues& previous);

  // Set once the solve has stopped (by PlanNext or a capped round in Apply), with the reason.
  const std::optional<std::string>& stop_reason() const { return stop_; }
  // The state at the current round boundary (its vectors copied).
  SolveState State() const;
  // After the last round: the solution and its stats (threads: what computed the batches).
  SolveResult Finish(double seconds, uint32_t threads) const;
  // Times a sample of `plan`'s rays against a sample of the final gather's, both traced by
  // `trace` as the solve traces its rounds (core/ray_cost_probe.h), once per solve: only while a
  // gather is pending and `plan` shoots. It traces about 2% of the gather's rays again (at most
  // 262,144); their results are thrown away, so the solve's bits do not depend on it. Progress
  // reports the ratio. The farm master does not call it (its agents trace, it has no caster), so
  // its ETA prices gather rays at the shooting rate.
  void MeasureGatherRayCost(const RoundPlan& plan, uint32_t batch_rays, const RayCostTracer& trace);
  // After Apply of `plan`: how far the solve has come, for progress displays (the gather still to
  // come on the mesh as it is now, after any refinement step).
  RoundProgress Progress(const RoundPlan& plan, const AppliedRound& applied) const;

  const PatchScene& scene() const { return *scene_; }
  // The mesh (null for a bare scene); a refinement step replaces it.
  const PatchMesh* mesh() const { return mesh_.get(); }
  std::unique_ptr<PatchMesh> TakeMesh() { return std::move(mesh_); }
  // Moves whenever the mesh, scene and solver are replaced by a refinement step.
  uint32_t mesh_generation() const { return refinements_; }
  // Steps that split (or restarted) since Start.
  uint32_t refinements() const { return refinements_; }
  bool refined() const { return refined_; }
  // Whether refinement is on: the mesh may still change at a refinement point.
  bool refines() const { return schedule_.has_value(); }
  const ProgressiveSolver& solver() const { return *solver_; }
  const SolverSettings& settings() const { return settings_; }
  // The budgets the rounds stop at (SolveBudget): the display after the solve spends the rest.
  const SolverSettings& budget() const { return budget_; }
  // What budget() leaves: the rays (the start's shadow rays count) and the seconds after `seconds`
  // spent in all; nullopt where there is no such budget. For progress estimates.
  std::optional<uint64_t> BudgetRaysLeft() const;
  std::optional<double> BudgetSecondsLeft(double seconds) const;
  // The rays the display is expected to cast after the solve of the current mesh
  // (core/display_budget.h DisplayRaysForecast), for estimates that include it.
  uint64_t display_rays_forecast() const { return display_forecast_; }
  const SolveTotals& totals() const { return totals_; }
  // The ray caster of the current scene, built on first use.
  const RayCaster& caster();
  // Frees the caster (the next caster() builds it again); no BatchTracer of it may be left.
  void ReleaseCaster() { caster_.reset(); }

 private:
  RoundDriver(const SolverSettings& settings, ThreadPool* pool);
  Status Resume(const SolveState& state);
  // Apply's bookkeeping once the solver has the round: totals, stop, refinement step.
  AppliedRound AfterApply(const RoundPlan& plan, uint64_t escaped_rays, uint64_t back_rays,
                          double seconds);
  void Install(RefinementStep step);
  // The rays the budget has counted so far: the rounds' and the start's shadow rays.
  uint64_t RaysSpent() const { return totals_.rays + solver_->start_rays(); }
  // The solver's settings for the current phase of the schedule (fewer rays before a restart).
  SolverSettings PhaseSettings() const;
  void RebuildSolver();

  SolverSettings settings_;
  StartLightSource start_;   // empty: each solver traces its own start
  LightScoreSource scores_;  // empty: refinement steps score on pool_
  // The budgets the rounds stop at: settings_'s less the display's share (core/display_budget.h).
  SolverSettings budget_;
  ThreadPool* pool_ = nullptr;                     // null for a bare scene
  std::unique_ptr<PatchMesh> mesh_;                // stable address: the solver refers to its scene
  std::unique_ptr<const PatchScene> owned_scene_;  // StartOwning's scene (no mesh)
  const PatchScene* scene_ = nullptr;              // mesh_'s, or the bare scene
  std::optional<RefinementSchedule> schedule_;     // refinement on
  std::unique_ptr<ProgressiveSolver> solver_;
  std::unique_ptr<RayCaster> caster_;  // for scene_, built on demand
  SolveTotals totals_;
  std::optional<std::string> stop_;
  bool time_capped_ = false;  // the last plan was trimmed to the time left, not the rays left
  uint32_t last_round_ = 0;   // the plan's round number of the last round applied
  uint32_t last_shooters_ = 0;
  uint32_t refinements_ = 0;
  bool refined_ = false;                   // the mesh is no longer the one given
  std::optional<double> gather_ray_cost_;  // MeasureGatherRayCost's ratio
  uint64_t display_forecast_ = 0;          // made with each solver (RebuildSolver)
  bool gather_ray_cost_tried_ = false;
};

}  // namespace radfarm
