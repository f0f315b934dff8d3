#include "core/solve.h"

#include <chrono>
#include <memory>

#include "core/batch_runner.h"
#include "core/ray_caster.h"
#include "core/thread_pool.h"

namespace radfarm {

SolveResult Solve(const PatchScene& scene, const SolverSettings& settings,
                  const std::function<void(const RoundProgress&)>& on_round) {
  const auto start = std::chrono::steady_clock::now();
  auto elapsed = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  ThreadPool pool(settings.threads);
  const RayCaster caster(scene);
  ProgressiveSolver solver(scene, settings);
  std::vector<std::unique_ptr<BatchRunner>> runners;
  for (unsigned w = 0; w < pool.size(); ++w) {
    runners.push_back(std::make_unique<BatchRunner>(scene, caster, solver.sampler()));
  }

  SolveStats stats;
  stats.stop_reason = "converged";
  while (solver.UnshotFraction() > settings.tolerance) {
    if (settings.max_rays > 0 && stats.rays >= settings.max_rays) {
      stats.stop_reason = "ray budget";
      break;
    }
    if (settings.max_seconds > 0 && elapsed() >= settings.max_seconds) {
      stats.stop_reason = "time budget";
      break;
    }
    const uint64_t cap = settings.max_rays > 0 ? settings.max_rays - stats.rays : 0;
    const RoundPlan plan = solver.PlanRound(kLocalBatchRays, cap);
    if (plan.batches.empty()) break;
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
    if (on_round) {
      on_round({solver.rounds_done(), stats.rays, elapsed(), solver.UnshotFraction(),
                settings.tolerance, &solver.energy()});
    }
    if (plan.capped && solver.UnshotFraction() > settings.tolerance) {
      stats.stop_reason = "ray budget";
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
  return {solver.radiosity(), solver.unshot(), stats};
}

}  // namespace radfarm
