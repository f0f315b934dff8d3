#include "solve/local_solve.h"

#include <algorithm>
#include <chrono>
#include <mutex>
#include <span>
#include <utility>

namespace radfarm {
namespace {

// The share of a sample's pace (SampleRaysPerSecond) a first round under a time budget is planned
// at.
constexpr double kSampledPaceShare = 0.5;

// Rays per second of `plan` on `batches`, timed on about 1% of its rays (at least a batch, at
// most 1M rays), traced again with their results thrown away: a ray's fate is a pure function of
// (seed, round, shooter, ray), so this changes no bit of the solve. 0 when too fast to time.
double SampleRaysPerSecond(RoundDriver& driver, LocalBatches& batches, const RoundPlan& plan) {
  const uint64_t wanted = std::clamp<uint64_t>(plan.rays / 100, 1, 1u << 20);
  const size_t stride = std::max<size_t>(1, size_t(plan.rays / wanted / kLocalBatchRays));
  std::vector<Batch> sample;
  uint64_t rays = 0;
  for (size_t b = 0; b < plan.batches.size() && rays < wanted; b += stride) {
    sample.push_back(plan.batches[b]);
    rays += plan.batches[b].ray_count;
  }
  // Not the BVH's build: on a big scene that alone would halve the pace measured, and the first
  // round would be cut to half the time left (and the solve stop there).
  batches.Prepare(driver);
  const auto start = std::chrono::steady_clock::now();
  batches.TraceOnly(driver, sample);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return seconds > 0 ? double(rays) / seconds : 0;
}

// Runs the driver's rounds on `pool` until it stops; returns the seconds spent in all.
// `spent_before` (reading and meshing the scene) counts toward the time budget only.
double RunRounds(RoundDriver& driver, ThreadPool& pool,
                 const std::function<void(const RoundProgress&)>& on_round,
                 const std::function<void(const SolveState&)>& after_round,
                 const std::function<void(const RoundRunning&)>& during_round,
                 double seconds_before, std::chrono::steady_clock::time_point start,
                 double spent_before = 0) {
  auto elapsed = [&] {
    return seconds_before +
           std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  auto budget_elapsed = [&] { return elapsed() + spent_before; };
  const bool time_budget = driver.settings().max_seconds > 0;
  double rays_per_second = 0;  // the pace of the rounds, to keep the next within the budget
  bool round_timed = false;    // rays_per_second is a round's, not the first round's sample
  LocalBatches batches(pool);
  while (true) {
    std::optional<RoundPlan> plan =
        driver.PlanNext(kLocalBatchRays, budget_elapsed(), rays_per_second);
    if (plan && time_budget && rays_per_second == 0) {
      // No pace yet (the first round, often the longest): time a sample of it, plan again. A
      // round also folds its results, which the sample does not: at 88,750 patches the sample
      // read 11.9 M rays/s and the first round 6.7, so the round is planned at half the sample's
      // pace (a first round cut short leaves its time to the rounds after it, which are paced
      // by the rounds' own measured pace).
      rays_per_second = kSampledPaceShare * SampleRaysPerSecond(driver, batches, *plan);
      if (rays_per_second > 0) {
        plan = driver.PlanNext(kLocalBatchRays, budget_elapsed(), rays_per_second);
      }
    }
    if (!plan) break;
    if (on_round) {  // for the ETA; not part of the round's time
      driver.MeasureGatherRayCost(*plan, kLocalBatchRays, [&](const std::vector<Batch>& sample) {
        batches.TraceOnly(driver, sample);
      });
    }
    const double round_start = elapsed();
    const double unshot_before = driver.solver().UnshotFraction();
    std::unique_ptr<RoundReduction> reduction = driver.Reduction(*plan);
    std::function<void(uint64_t)> on_batch;
    if (during_round) {
      on_batch = [&](uint64_t rays_done) {
        during_round({plan->round, plan->rays, rays_done, elapsed() - round_start, plan->gather,
                      driver.BudgetSecondsLeft(budget_elapsed())});
      };
    }
    batches.Reduce(driver, *plan, *reduction, on_batch);
    // The best pace seen: a short round's fixed costs make it look slow, and its pace would trim
    // a long round (the gather) far short of the budget.
    const double traced = elapsed() - round_start;
    // The sample is tracing alone; a round also folds its results, so the sample's pace is too
    // fast and a gather planned at it overruns the budget: a timed round replaces it.
    if (traced > 0) {
      const double pace = double(plan->rays) / traced;
      rays_per_second = round_timed ? std::max(rays_per_second, pace) : pace;
      round_timed = true;
    }
    const AppliedRound applied = driver.Apply(*plan, *reduction, elapsed());
    if (on_round) {
      RoundProgress progress = driver.Progress(*plan, applied);
      progress.round_rays = plan->rays;
      // A refinement step is no part of a round's pace: it comes once, when it comes.
      progress.round_seconds = elapsed() - round_start - applied.refine_seconds;
      progress.unshot_before = unshot_before;
      progress.budget_rays_left = driver.BudgetRaysLeft();
      progress.budget_seconds_left = driver.BudgetSecondsLeft(budget_elapsed());
      on_round(progress);
    }
    if (after_round) after_round(driver.State());
  }
  return elapsed();
}

// Group g of `batches` as BatchTracer::GroupStarts cut them.
std::span<const Batch> GroupOf(const std::vector<Batch>& batches, const std::vector<size_t>& starts,
                               size_t g) {
  return std::span(batches).subspan(starts[g], starts[g + 1] - starts[g]);
}

}  // namespace

void LocalBatches::Prepare(RoundDriver& driver) {
  if (driver_ == &driver && generation_ == driver.mesh_generation() && !tracers_.empty()) return;
  tracers_.clear();
  for (unsigned w = 0; w < pool_.size(); ++w) {
    tracers_.push_back(
        std::make_unique<BatchTracer>(driver.scene(), driver.caster(), driver.solver().sampler()));
  }
  driver_ = &driver;
  generation_ = driver.mesh_generation();
}

std::vector<BatchResult> LocalBatches::Run(RoundDriver& driver, const RoundPlan& plan) {
  Prepare(driver);
  std::vector<BatchResult> results(plan.batches.size());
  const std::vector<size_t> starts = BatchTracer::GroupStarts(plan.batches);
  pool_.ParallelFor(starts.size() - 1, [&](unsigned worker, size_t g) {
    tracers_[worker]->RunMany(GroupOf(plan.batches, starts, g), results.data() + starts[g]);
  });
  return results;
}

void LocalBatches::TraceOnly(RoundDriver& driver, const std::vector<Batch>& batches) {
  Prepare(driver);
  const std::vector<size_t> starts = BatchTracer::GroupStarts(batches);
  pool_.ParallelFor(starts.size() - 1, [&](unsigned worker, size_t g) {
    std::vector<BatchResult> results(starts[g + 1] - starts[g]);
    tracers_[worker]->RunMany(GroupOf(batches, starts, g), results.data());
  });
}

void LocalBatches::Reduce(RoundDriver& driver, const RoundPlan& plan, RoundReduction& reduction,
                          const std::function<void(uint64_t rays_done)>& on_batch) {
  Prepare(driver);
  // The pool hands out groups of batches in increasing order, so the reduction's frontier trails
  // the newest batch by about one group per thread, and that is all it holds.
  std::mutex mutex;
  uint64_t rays_done = 0;
  const std::vector<size_t> starts = BatchTracer::GroupStarts(plan.batches);
  pool_.ParallelFor(starts.size() - 1, [&](unsigned worker, size_t g) {
    std::vector<BatchResult> results(starts[g + 1] - starts[g]);
    tracers_[worker]->RunMany(GroupOf(plan.batches, starts, g), results.data());
    std::lock_guard lock(mutex);
    for (size_t b = starts[g]; b < starts[g + 1]; ++b) {
      reduction.Add(b, std::move(results[b - starts[g]]));
      rays_done += plan.batches[b].ray_count;
      if (on_batch) on_batch(rays_done);
    }
  });
}

Result<RefiningSolveResult> SolveRefining(PatchMesh mesh, const SolverSettings& settings,
                                          const RefineSettings& refine,
                                          const std::function<void(const RoundProgress&)>& on_round,
                                          const RefiningHooks& hooks) {
  const auto start = std::chrono::steady_clock::now();
  const double seconds_before = hooks.resume != nullptr ? hooks.resume->totals.seconds : 0;
  RefiningSolveResult out;
  out.patches_before = mesh.patch_scene().patches.size();
  ThreadPool pool(settings.threads);
  Result<std::unique_ptr<RoundDriver>> driver =
      RoundDriver::Start(std::move(mesh), settings, refine, hooks.resume, pool, hooks.start);
  if (!driver) return Error{driver.error()};
  if (hooks.previous != nullptr) {
    if (refine.enabled || hooks.resume != nullptr) {
      return Error{"a re-bake does not combine with adaptive refinement or a resumed render"};
    }
    if (Status s = (*driver)->WarmStart(*hooks.previous); !s) return Error{s.error()};
  }
  const double start_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (hooks.after_start) hooks.after_start(start_seconds, (*driver)->solver().start_rays());
  const double seconds = RunRounds(**driver, pool, on_round, hooks.after_round, hooks.during_round,
                                   seconds_before, start, hooks.seconds_spent_before);
  out.solution = (*driver)->Finish(seconds, pool.size());
  out.solution.stats.start_seconds = start_seconds;
  out.refinements = (*driver)->refinements();
  out.mesh = (*driver)->TakeMesh();
  return out;
}

SolveResult Solve(const PatchScene& scene, const SolverSettings& settings,
                  const std::function<void(const RoundProgress&)>& on_round,
                  const SolveState* resume,
                  const std::function<void(const SolveState&)>& after_round) {
  const auto start = std::chrono::steady_clock::now();
  const double seconds_before = resume != nullptr ? resume->totals.seconds : 0;
  ThreadPool pool(settings.threads);
  std::unique_ptr<RoundDriver> driver = RoundDriver::Start(scene, settings, resume);
  const double seconds = RunRounds(*driver, pool, on_round, after_round, {}, seconds_before, start);
  return driver->Finish(seconds, pool.size());
}

}  // namespace radfarm
