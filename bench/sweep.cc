#include "bench/sweep.h"

#include <algorithm>
#include <cstdio>
#include <utility>

#include "bench/patch_error.h"
#include "bench/stopwatch.h"
#include "bench/timed_solve.h"
#include "solve/local_solve.h"

namespace radfarm::bench {
namespace {

std::string FormatCount(uint64_t n) {
  char text[32];
  if (n >= 1000000) {
    std::snprintf(text, sizeof text, "%.3gM", double(n) / 1e6);
  } else if (n >= 1000) {
    std::snprintf(text, sizeof text, "%.3gk", double(n) / 1e3);
  } else {
    std::snprintf(text, sizeof text, "%llu", static_cast<unsigned long long>(n));
  }
  return text;
}

}  // namespace

Reference ComputeReference(const BenchScene& scene, const SweepConfig& config) {
  Reference ref;
  ref.settings.sampler = SamplerKind::kSobol;
  ref.settings.seed = config.reference_seed;
  ref.settings.tolerance = config.reference_tolerance;
  ref.settings.shot_rays =
      config.reference_factor * *std::max_element(config.shot_rays.begin(), config.shot_rays.end());
  const Stopwatch clock;
  SolveResult solved = Solve(scene.patches(), ref.settings);
  ref.seconds = clock.Seconds();
  ref.rays = solved.stats.rays;
  ref.rounds = solved.stats.rounds;
  ref.radiosity = std::move(solved.radiosity);
  ref.patches = ClassifyPatches(ref.radiosity);
  std::printf(
      "%s: reference (sobol, seed %llu, shot_rays %s, tolerance %g): %s rays, %llu rounds, "
      "%.1f s\n",
      scene.name.c_str(), static_cast<unsigned long long>(ref.settings.seed),
      FormatCount(ref.settings.shot_rays).c_str(), ref.settings.tolerance,
      FormatCount(ref.rays).c_str(), static_cast<unsigned long long>(ref.rounds), ref.seconds);
  std::fflush(stdout);
  return ref;
}

SweepPoint ScorePoint(const TimedSolve& timed, const SolverSettings& settings, std::string budget,
                      const Reference& reference) {
  SweepPoint point;
  point.settings = settings;
  point.budget = std::move(budget);
  point.rays = timed.result.stats.rays;
  point.rounds = timed.result.stats.rounds;
  point.seconds = timed.median_seconds;
  point.rays_per_second = point.seconds > 0 ? double(point.rays) / point.seconds : 0;
  point.error =
      RmsRelativeError(timed.result.radiosity, reference.radiosity, reference.patches.all);
  point.error_lit =
      RmsRelativeError(timed.result.radiosity, reference.radiosity, reference.patches.lit);
  point.unshot_fraction = timed.result.stats.unshot_fraction;
  point.stop_reason = timed.result.stats.stop_reason;
  return point;
}

SweepPoint RunPoint(const BenchScene& scene, const SolverSettings& settings, std::string budget,
                    const Reference& reference, int repetitions) {
  return ScorePoint(RunTimedSolve(scene.patches(), settings, repetitions), settings,
                    std::move(budget), reference);
}

SceneSweep RunSweep(const BenchScene& scene, const SweepConfig& config) {
  SceneSweep sweep;
  sweep.scene = scene.name;
  sweep.path = scene.path;
  sweep.patches = scene.patches().patches.size();
  sweep.patch_size = scene.mesh->patch_size();
  sweep.load_seconds = scene.load_seconds;
  sweep.reference = ComputeReference(scene, config);

  SolverSettings base;
  base.tolerance = config.tolerance;
  base.seed = config.seed;
  uint64_t top_rung_rays = 0;
  for (uint64_t shot_rays : config.shot_rays) {
    SolverSettings sobol = base;
    sobol.sampler = SamplerKind::kSobol;
    sobol.shot_rays = shot_rays;
    SolverSettings random = sobol;
    random.sampler = SamplerKind::kRandom;
    SolverSettings grid = base;
    grid.sampler = SamplerKind::kGrid;
    grid.grid_step_degrees = config.grid_step_degrees;
    grid.shooters_per_round = config.grid_shooters_per_round;
    // A rung's samplers run alternately, so that they see the same load on a shared machine. The
    // grid's budget is the Sobol run's ray count, known after its first run.
    TimedSolve timed_sobol, timed_random, timed_grid;
    for (int rep = 0; rep < std::max(1, config.repetitions); ++rep) {
      AddTimedRun(scene.patches(), sobol, &timed_sobol);
      AddTimedRun(scene.patches(), random, &timed_random);
      grid.max_rays = timed_sobol.result.stats.rays;
      AddTimedRun(scene.patches(), grid, &timed_grid);
    }
    const std::string budget = "shot_rays " + FormatCount(shot_rays);
    char grid_budget[96];
    std::snprintf(grid_budget, sizeof grid_budget, "%g°, max_rays %s", grid.grid_step_degrees,
                  FormatCount(grid.max_rays).c_str());
    for (SweepPoint point : {ScorePoint(timed_sobol, sobol, budget, sweep.reference),
                             ScorePoint(timed_random, random, budget, sweep.reference),
                             ScorePoint(timed_grid, grid, grid_budget, sweep.reference)}) {
      PrintPoint(scene.name, point);
      sweep.points.push_back(std::move(point));
    }
    top_rung_rays = std::max(top_rung_rays, grid.max_rays);
  }

  for (double step : config.grid_steps) {
    SolverSettings g = base;
    g.sampler = SamplerKind::kGrid;
    g.grid_step_degrees = step;
    g.shooters_per_round = config.grid_shooters_per_round;
    g.max_rays = top_rung_rays;
    char budget[96];
    std::snprintf(budget, sizeof budget, "%g°, max_rays %s", step, FormatCount(g.max_rays).c_str());
    // The grid line already ran this step at this budget: reuse it rather than time it twice.
    const auto same =
        std::find_if(sweep.points.begin(), sweep.points.end(), [&](const SweepPoint& p) {
          return p.settings.sampler == SamplerKind::kGrid && p.settings.grid_step_degrees == step &&
                 p.settings.max_rays == g.max_rays;
        });
    if (same != sweep.points.end()) {
      sweep.grid_steps.push_back(*same);
      continue;
    }
    sweep.grid_steps.push_back(RunPoint(scene, g, budget, sweep.reference, config.repetitions));
    PrintPoint(scene.name, sweep.grid_steps.back());
  }

  for (double step : config.grid_converged_steps) {
    SolverSettings g = base;
    g.sampler = SamplerKind::kGrid;
    g.grid_step_degrees = step;
    g.shooters_per_round = config.grid_shooters_per_round;
    char budget[96];
    std::snprintf(budget, sizeof budget, "%g°, to tolerance", step);
    sweep.grid_converged.push_back(RunPoint(scene, g, budget, sweep.reference, config.repetitions));
    PrintPoint(scene.name, sweep.grid_converged.back());
  }
  return sweep;
}

void PrintPoint(const std::string& scene, const SweepPoint& p) {
  std::printf(
      "%s: %-6s %-24s %10llu rays %6llu rounds %8.3f s %6.2f Mrays/s  error %.4f, lit %.4f  (%s)\n",
      scene.c_str(), std::string(SamplerName(p.settings.sampler)).c_str(), p.budget.c_str(),
      static_cast<unsigned long long>(p.rays), static_cast<unsigned long long>(p.rounds), p.seconds,
      p.rays_per_second / 1e6, p.error, p.error_lit, p.stop_reason.c_str());
  std::fflush(stdout);
}

}  // namespace radfarm::bench
