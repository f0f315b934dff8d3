#include "bench/progress/eta_trace.h"

#include <chrono>
#include <cmath>
#include <mutex>
#include <stdexcept>

#include "core/progress_estimator.h"
#include "input/input_scene.h"
#include "input/scene_loader.h"
#include "job/job.h"
#include "mesh/patch_mesh.h"
#include "solve/local_solve.h"

namespace radfarm::bench {

EtaTrace TraceJob(const std::string& name, const std::string& job_path, unsigned threads) {
  Result<Job> job = LoadJob(job_path);
  if (!job) throw std::runtime_error(job.error());
  Result<InputScene> input = LoadScene(job->scene_path);
  if (!input) throw std::runtime_error(input.error());
  std::vector<std::string> warnings;
  Result<PatchMesh> mesh = PatchMesh::Build(*input, job->mesh, &warnings);
  if (!mesh) throw std::runtime_error(mesh.error());

  EtaTrace trace;
  trace.scene = name;
  trace.patches = mesh->patch_scene().patches.size();
  trace.threads = threads;
  SolverSettings settings = job->solver;
  settings.threads = threads;
  ProgressEstimator estimator(settings.tolerance);
  SolvePosition position;
  std::mutex mutex;  // during_round runs on a worker
  const auto start = std::chrono::steady_clock::now();
  auto now = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  auto record = [&](uint32_t round, bool in_gather, const ProgressEstimate& e) {
    trace.points.push_back(
        {round, in_gather, now(), e.seconds_left ? *e.seconds_left : -1.0, 0, e.fraction});
  };
  struct {
    double rays = 0, seconds = 0;
  } shooting, gather;  // the rounds of each kind, for gather_ray_cost_seen
  RefiningHooks hooks;
  uint32_t rounds = 0;
  double next_tenth = 0.1;
  hooks.during_round = [&](const RoundRunning& r) {
    if (!r.gather) return;
    std::lock_guard lock(mutex);
    const double part = double(r.round_rays_done) / double(r.round_rays);
    if (part < next_tenth || r.round_rays_done >= r.round_rays) return;
    next_tenth = std::floor(part * 10) / 10 + 0.1;
    SolvePosition at = position;
    at.round_rays = r.round_rays;
    at.round_rays_done = r.round_rays_done;
    at.round_seconds = r.round_seconds;
    at.round_gather = true;
    record(rounds, true, estimator.Estimate(at));
  };
  Result<RefiningSolveResult> solved = SolveRefining(
      std::move(*mesh), settings, job->refine,
      [&](const RoundProgress& p) {
        std::lock_guard lock(mutex);
        estimator.SetGatherRayCost(p.gather_ray_cost);
        trace.gather_ray_cost_probed = p.gather_ray_cost;
        (p.gather ? gather : shooting).rays += double(p.round_rays);
        (p.gather ? gather : shooting).seconds += p.round_seconds;
        estimator.AddRound(
            {p.round_rays, p.round_seconds, p.unshot_before, p.unshot_fraction, p.gather});
        position = {p.rays, p.unshot_fraction, p.gather_rays_left};
        rounds = p.round;
        if (!p.gather) record(p.round, false, estimator.Estimate(position));
      },
      hooks);
  if (!solved) throw std::runtime_error(solved.error());
  trace.seconds = now();
  trace.rays = solved->solution.stats.rays;
  if (gather.rays > 0 && shooting.rays > 0 && shooting.seconds > 0) {
    trace.gather_ray_cost_seen =
        (gather.seconds / gather.rays) / (shooting.seconds / shooting.rays);
  }
  for (EtaPoint& point : trace.points) point.actual_left = trace.seconds - point.seconds;
  return trace;
}

}  // namespace radfarm::bench
