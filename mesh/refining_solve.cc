#include "mesh/refining_solve.h"

#include <algorithm>
#include <chrono>
#include <iterator>
#include <utility>
#include <vector>

#include "core/batch_runner.h"
#include "core/ray_caster.h"
#include "core/solve_control.h"
#include "core/thread_pool.h"
#include "mesh/refine.h"

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

Result<RefiningSolveResult> SolveRefining(
    PatchMesh mesh, const SolverSettings& settings, const RefineSettings& refine,
    const std::function<void(const RoundProgress&)>& on_round) {
  RefiningSolveResult out;
  out.patches_before = mesh.patch_scene().patches.size();
  out.mesh = std::make_unique<PatchMesh>(std::move(mesh));
  if (!refine.enabled) {
    out.solution = Solve(out.mesh->patch_scene(), settings, on_round);
    return out;
  }
  Result<ResolvedRefineSettings> resolved = ResolveRefineSettings(
      refine, out.mesh->patch_size(), out.patches_before, out.mesh->weld_tolerance());
  if (!resolved.ok()) return Error{resolved.error()};

  const auto start = std::chrono::steady_clock::now();
  auto elapsed = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  ThreadPool pool(settings.threads);
  auto stage = std::make_unique<Stage>(out.mesh->patch_scene(), settings, pool.size());
  auto refine_step = [&](double ray_power, bool restart) {
    ProgressiveSolver& solver = stage->solver();
    RefinedMesh refined = Refine(*out.mesh, solver.radiosity(), solver.unshot(), ray_power,
                                 *resolved, stage->caster(), pool);
    if (refined.split == 0) return;
    const uint32_t rounds = solver.rounds_done();
    CarriedState carried = CarryOver(refined, solver.energy(), restart);
    stage.reset();  // it refers to the old mesh's scene
    *out.mesh = std::move(refined.mesh);
    stage = std::make_unique<Stage>(out.mesh->patch_scene(), settings, pool.size());
    stage->solver().Restore(rounds, std::move(carried.radiosity), std::move(carried.unshot),
                            carried.energy);
    ++out.refinements;
  };

  refine_step(0, false);
  size_t next_point = 0;
  SolveStats& stats = out.solution.stats;
  stats.stop_reason = kStopConverged;
  while (true) {
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
                settings.tolerance, &solver.energy()});
    }
    if (auto stop = StopAfterRound(plan, solver, settings)) {
      stats.stop_reason = *stop;
      break;
    }
    const RefinePoint* point = PassedRefinePoint(solver.UnshotFraction(), &next_point);
    if (point != nullptr) {
      refine_step(RayPower(solver.energy().emitted, settings.shot_rays,
                           out.mesh->patch_scene().patches.size()),
                  point->restart);
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
  return out;
}

}  // namespace radfarm
