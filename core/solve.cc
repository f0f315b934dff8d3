#include "core/solve.h"

#include <chrono>
#include <memory>

#include "core/batch_runner.h"
#include "core/ray_caster.h"
#include "core/solve_control.h"
#include "core/thread_pool.h"

namespace radfarm {

SolveResult Solve(const PatchScene& scene, const SolverSettings& settings,
                  const std::function<void(const RoundProgress&)>& on_round,
                  const SolveHooks& hooks) {
  const auto start = std::chrono::steady_clock::now();
  const double seconds_before = hooks.resume ? hooks.resume->seconds : 0;
  auto elapsed = [&] {
    return seconds_before +
           std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  ThreadPool pool(settings.threads);
  const RayCaster caster(scene);
  ProgressiveSolver solver(scene, settings);
  std::vector<std::unique_ptr<BatchRunner>> runners;
  for (unsigned w = 0; w < pool.size(); ++w) {
    runners.push_back(std::make_unique<BatchRunner>(scene, caster, solver.sampler()));
  }

  SolveStats stats;
  stats.stop_reason = kStopConverged;
  if (const SolveCheckpoint* c = hooks.resume) {
    solver.Restore(c->rounds_done, c->radiosity, c->unshot, c->energy);
    stats.rays = c->rays;
    stats.escaped_rays = c->escaped_rays;
    stats.backface_hits = c->backface_hits;
  }
  while (true) {
    if (auto stop = StopBeforeRound(solver, settings, stats.rays, elapsed())) {
      stats.stop_reason = *stop;
      break;
    }
    const RoundPlan plan = solver.PlanRound(kLocalBatchRays, NextRoundRayCap(settings, stats.rays));
    if (plan.batches.empty()) break;  // nothing left to shoot: converged
    std::vector<BatchResult> results(plan.batches.size());
    pool.ParallelFor(plan.batches.size(), [&](unsigned worker, size_t b) {
      results[b] = runners[worker]->Run(plan.batches[b]);
    });
    for (const BatchResult& r : results) {
      stats.escaped_rays += r.escaped_rays;
      stats.backface_hits += r.back_rays;
    }
    solver.ApplyRound(plan, results);
    stats.rays += plan.rays;
    if (hooks.after_round) {
      hooks.after_round({plan.round, solver.rounds_done(), solver.radiosity(), solver.unshot(),
                         solver.energy(), stats.rays, stats.escaped_rays, stats.backface_hits,
                         elapsed(), static_cast<uint32_t>(plan.shots.size())});
    }
    if (on_round) {
      on_round({solver.rounds_done(), stats.rays, elapsed(), solver.UnshotFraction(),
                settings.tolerance, &solver.energy(), plan.gather, solver.PendingGatherRays()});
    }
    if (auto stop = StopAfterRound(plan, solver, settings)) {
      stats.stop_reason = *stop;
      break;
    }
  }

  stats.rounds = solver.rounds_done();
  stats.seconds = elapsed();
  stats.rays_per_second = stats.seconds > 0 ? double(stats.rays) / stats.seconds : 0;
  stats.patches = scene.patches.size();
  stats.unshot_fraction = solver.UnshotFraction();
  stats.threads = pool.size();
  stats.seed = settings.seed;
  stats.sampler = std::string(SamplerName(settings.sampler));
  stats.emitted_power = solver.energy().emitted;
  stats.absorbed_power = solver.energy().absorbed;
  stats.escaped_power = solver.energy().escaped;
  return {solver.radiosity(), solver.unshot(), stats, solver.direct_light()};
}

}  // namespace radfarm
