#include "mesh/refining_solve.h"

#include <algorithm>
#include <chrono>
#include <iterator>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/batch_runner.h"
#include "core/ray_caster.h"
#include "core/solve_control.h"
#include "core/thread_pool.h"
#include "mesh/refine.h"
#include "mesh/refinement_schedule.h"

namespace radfarm {
namespace {

// What a round needs, built for one mesh; rebuilt after every refinement that splits something.
class Stage {
 public:
  Stage(const PatchScene& scene, const SolverSettings& settings, unsigned workers)
      : caster_(scene), solver_(scene, settings) {
    for (unsigned w = 0; w < workers; ++w) {
      runners_.push_back(std::make_unique<BatchRunner>(scene, caster_, solver_.sampler()));
    }
  }
  const RayCaster& caster() const { return caster_; }
  ProgressiveSolver& solver() { return solver_; }
  BatchRunner& runner(unsigned worker) { return *runners_[worker]; }

 private:
  RayCaster caster_;
  ProgressiveSolver solver_;
  std::vector<std::unique_ptr<BatchRunner>> runners_;
};

}  // namespace

Result<RefiningSolveResult> SolveRefining(PatchMesh mesh, const SolverSettings& settings,
                                          const RefineSettings& refine,
                                          const std::function<void(const RoundProgress&)>& on_round,
                                          const RefiningHooks& hooks) {
  RefiningSolveResult out;
  out.patches_before = mesh.patch_scene().patches.size();
  out.mesh = std::make_unique<PatchMesh>(std::move(mesh));
  const RefiningResume* resume = hooks.resume ? &*hooks.resume : nullptr;
  // Without refinement the loop below is Solve()'s, step for step: no schedule, no step.
  std::optional<RefinementSchedule> schedule;
  if (refine.enabled) {
    Result<RefinementSchedule> created = RefinementSchedule::Create(
        refine, *out.mesh, settings.shot_rays, resume != nullptr ? resume->next_point : 0);
    if (!created.ok()) return Error{created.error()};
    schedule.emplace(std::move(*created));
  } else if (resume != nullptr && resume->refined_scene != nullptr) {
    return Error{"cannot resume an unrefined solve on a refined mesh"};
  }
  bool refined = false;  // the mesh is no longer the one given
  if (resume != nullptr && resume->refined_scene != nullptr) {
    PatchMesh rebuilt = out.mesh->Rebuilt(PatchMesh::PiecesOf(*resume->refined_scene));
    if (rebuilt.patch_scene().patches.size() != resume->refined_scene->patches.size()) {
      return Error{"the refined mesh to resume on has " +
                   std::to_string(resume->refined_scene->patches.size()) +
                   " elements, rebuilt it has " +
                   std::to_string(rebuilt.patch_scene().patches.size())};
    }
    *out.mesh = std::move(rebuilt);
    refined = true;
  }
  if (resume != nullptr &&
      resume->solve->radiosity.size() != out.mesh->patch_scene().patches.size()) {
    return Error{"the state to resume holds " + std::to_string(resume->solve->radiosity.size()) +
                 " elements, the mesh " + std::to_string(out.mesh->patch_scene().patches.size())};
  }

  const auto start = std::chrono::steady_clock::now();
  const double seconds_before = resume != nullptr ? resume->solve->seconds : 0;
  auto elapsed = [&] {
    return seconds_before +
           std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  ThreadPool pool(settings.threads);
  // The solver's settings for the current phase of the schedule (fewer rays before a restart).
  auto phase_settings = [&] {
    return schedule ? schedule->SolverSettingsNow(settings, out.mesh->patch_scene().patches.size())
                    : settings;
  };
  auto stage = std::make_unique<Stage>(out.mesh->patch_scene(), phase_settings(), pool.size());
  auto apply = [&](std::optional<RefinementStep> step) {
    if (!step) return;
    stage.reset();  // it refers to the old mesh's scene
    *out.mesh = std::move(step->mesh);
    stage = std::make_unique<Stage>(out.mesh->patch_scene(), phase_settings(), pool.size());
    RestoreStep(*step, stage->solver());
    refined = true;
    ++out.refinements;
  };

  SolveStats& stats = out.solution.stats;
  stats.stop_reason = kStopConverged;
  if (resume != nullptr) {
    const SolveCheckpoint& c = *resume->solve;
    stage->solver().Restore(c.rounds_done, c.radiosity, c.unshot, c.energy);
    stats.rays = c.rays;
    stats.escaped_rays = c.escaped_rays;
    stats.backface_hits = c.backface_hits;
    if (resume->stopped) stats.stop_reason = *resume->stopped;
  } else if (schedule) {
    apply(schedule->BeforeFirstRound(*out.mesh, stage->solver(), stage->caster(), pool));
  }
  // A resume from the round the solve stopped after runs no round: a round capped by the ray
  // budget may have left a few rays of it, which StopBeforeRound alone would spend.
  while (resume == nullptr || !resume->stopped) {
    ProgressiveSolver& solver = stage->solver();
    if (auto stop = StopBeforeRound(solver, settings, stats.rays, elapsed())) {
      stats.stop_reason = *stop;
      break;
    }
    const RoundPlan plan = solver.PlanRound(kLocalBatchRays, NextRoundRayCap(settings, stats.rays));
    if (plan.batches.empty()) break;
    std::vector<BatchResult> results(plan.batches.size());
    pool.ParallelFor(plan.batches.size(), [&](unsigned worker, size_t b) {
      results[b] = stage->runner(worker).Run(plan.batches[b]);
    });
    for (const BatchResult& r : results) {
      stats.escaped_rays += r.escaped_rays;
      stats.backface_hits += r.back_rays;
    }
    solver.ApplyRound(plan, results);
    stats.rays += plan.rays;
    if (on_round) {
      on_round({solver.rounds_done(), stats.rays, elapsed(), solver.UnshotFraction(),
                settings.tolerance, &solver.energy(), plan.gather, solver.PendingGatherRays()});
    }
    std::optional<std::string> stop = StopAfterRound(plan, solver, settings);
    if (!stop && schedule) apply(schedule->AfterRound(*out.mesh, solver, stage->caster(), pool));
    if (hooks.after_round) {
      const ProgressiveSolver& now = stage->solver();  // rebuilt if the round refined
      hooks.after_round({{plan.round, now.rounds_done(), now.radiosity(), now.unshot(),
                          now.energy(), stats.rays, stats.escaped_rays, stats.backface_hits,
                          elapsed(), static_cast<uint32_t>(plan.shots.size())},
                         refined ? &out.mesh->patch_scene() : nullptr,
                         out.refinements,
                         schedule ? static_cast<uint32_t>(schedule->next_point()) : 0u,
                         stop});
    }
    if (stop) {
      stats.stop_reason = *stop;
      break;
    }
  }

  const ProgressiveSolver& solver = stage->solver();
  stats.rounds = solver.rounds_done();
  stats.seconds = elapsed();
  stats.rays_per_second = stats.seconds > 0 ? double(stats.rays) / stats.seconds : 0;
  stats.patches = out.mesh->patch_scene().patches.size();
  stats.unshot_fraction = solver.UnshotFraction();
  stats.threads = pool.size();
  stats.seed = settings.seed;
  stats.sampler = std::string(SamplerName(settings.sampler));
  stats.emitted_power = solver.energy().emitted;
  stats.absorbed_power = solver.energy().absorbed;
  stats.escaped_power = solver.energy().escaped;
  out.solution.radiosity = solver.radiosity();
  out.solution.unshot = solver.unshot();
  out.solution.direct_light = solver.direct_light();
  return out;
}

}  // namespace radfarm
