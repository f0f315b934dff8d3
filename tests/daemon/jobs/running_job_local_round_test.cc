// RunningJob::RunLocally: a job whose every round the master computes itself ends with the
// radiosity `radfarm render` gives, to the bit (core/batch.h: a batch's result does not depend on
// where it runs). And RunningJob::Prepare plans the first round tapered for the agents known.
#include <gtest/gtest.h>

#include <algorithm>

#include "codec/job_bundle.h"
#include "daemon/jobs/running_job.h"
#include "input/input_scene.h"
#include "job/job.h"
#include "mesh/patch_mesh.h"
#include "solve/local_solve.h"

namespace radfarm::daemon {
namespace {

TEST(RunningJobLocalRoundTest, RoundsRunHereGiveTheLocalSolveBitForBit) {
  Result<Job> job = LoadJob(RADFARM_SOURCE_DIR "/scenes/cornell-box.toml");
  ASSERT_TRUE(job.ok()) << job.error();
  Result<InputScene> scene = LoadObjScene(job->scene_path);
  ASSERT_TRUE(scene.ok()) << scene.error();
  job->mesh.patch_size = 100;  // a small job: 307 patches
  job->solver.shot_rays = 200000;
  job->solver.gather_rays = 256;
  const codec::JobBundle bundle{*job, *scene};
  store::JobRecord record;
  record.id = 1;
  Result<std::shared_ptr<RunningJob>> runner = RunningJob::Prepare(
      record, codec::EncodeJobBundle(bundle), std::nullopt, std::nullopt, {}, {});
  ASSERT_TRUE(runner.ok()) << runner.error();
  RunningJob& r = **runner;

  std::vector<Rgb> radiosity;
  for (int rounds = 0; rounds < 1000; ++rounds) {
    ASSERT_GT(r.planned_rays(), 0u);
    Result<RoundPlan> plan = r.TakePlannedRound();
    ASSERT_TRUE(plan.ok()) << plan.error();
    EXPECT_EQ(r.phase(), RunningJob::Phase::kReducing);
    const scheduler::CompletedRound round = r.RunLocally(std::move(*plan));
    ASSERT_EQ(round.results.size(), round.plan.batches.size());
    RoundOutcome outcome = r.Reduce(round, 0.01, true, {4096, 0});
    radiosity = outcome.checkpoint.radiosity;
    if (!r.InstallOutcome(outcome)) break;
  }
  ASSERT_EQ(r.phase(), RunningJob::Phase::kFinished);
  EXPECT_EQ(r.planned_rays(), 0u);
  EXPECT_FALSE(r.TakePlannedRound().ok());

  Result<PatchMesh> mesh = PatchMesh::Build(*scene, job->mesh, nullptr);
  ASSERT_TRUE(mesh.ok()) << mesh.error();
  const SolveResult local = Solve(mesh->patch_scene(), job->solver);
  ASSERT_EQ(radiosity.size(), local.radiosity.size());
  for (size_t i = 0; i < radiosity.size(); ++i) ASSERT_EQ(radiosity[i], local.radiosity[i]) << i;
  EXPECT_EQ(r.totals().rays, local.stats.rays);
}

// The first round is planned before any agent is measured: batches of the default size, its end
// cut finer for the agents known when the job started (none known: not cut), the same rays.
TEST(RunningJobLocalRoundTest, TheFirstRoundIsTaperedForTheAgentsKnownAtTheStart) {
  Result<Job> job = LoadJob(RADFARM_SOURCE_DIR "/scenes/cornell-box.toml");
  ASSERT_TRUE(job.ok()) << job.error();
  Result<InputScene> scene = LoadObjScene(job->scene_path);
  ASSERT_TRUE(scene.ok()) << scene.error();
  job->mesh.patch_size = 100;
  job->solver.shot_rays = 50'000'000;  // shots of many default batches: only planned, not traced
  const std::vector<uint8_t> blob = codec::EncodeJobBundle(codec::JobBundle{*job, *scene});
  store::JobRecord record;
  record.id = 1;
  const scheduler::SchedulerOptions options;
  std::vector<RoundPlan> plans;
  for (size_t agents : {size_t{0}, size_t{4}}) {
    Result<std::shared_ptr<RunningJob>> runner =
        RunningJob::Prepare(record, blob, std::nullopt, std::nullopt, {}, options, {}, {}, agents);
    ASSERT_TRUE(runner.ok()) << runner.error();
    Result<RoundPlan> plan = (*runner)->TakePlannedRound();
    ASSERT_TRUE(plan.ok()) << plan.error();
    plans.push_back(std::move(*plan));
  }
  const RoundPlan& untapered = plans[0];
  const RoundPlan& tapered = plans[1];
  EXPECT_EQ(untapered.rays, tapered.rays);
  for (const Batch& b : untapered.batches) EXPECT_LE(b.ray_count, options.default_batch_rays);
  // 4 agents x taper_ways_per_agent = 12 ways: batches near the plan's end hold at most the rays
  // after them over 12, down to the floor, so the tapered plan ends in at least 12 more batches
  // under the default size, the last at most the floor.
  const auto short_batches = [&](const RoundPlan& plan) {
    return std::count_if(plan.batches.begin(), plan.batches.end(),
                         [&](const Batch& b) { return b.ray_count < options.default_batch_rays; });
  };
  EXPECT_GE(short_batches(tapered), short_batches(untapered) + 12);
  EXPECT_LE(tapered.batches.back().ray_count, TaperFloor(options.default_batch_rays));
}

// The Cornell box at 307 patches, with the budgets given, as the master prepares it (no agents
// known unless said, each reporting `reported_rays_per_second` in all).
std::shared_ptr<RunningJob> SmallBudgetedJob(uint64_t max_rays, double max_seconds,
                                             size_t agents = 0,
                                             double reported_rays_per_second = 0) {
  Result<Job> job = LoadJob(RADFARM_SOURCE_DIR "/scenes/cornell-box.toml");
  EXPECT_TRUE(job.ok()) << job.error();
  Result<InputScene> scene = LoadObjScene(job->scene_path);
  EXPECT_TRUE(scene.ok()) << scene.error();
  job->mesh.patch_size = 100;
  job->solver.shot_rays = 200000;
  job->solver.gather_rays = 256;
  job->solver.max_rays = max_rays;
  job->solver.max_seconds = max_seconds;
  store::JobRecord record;
  record.id = 1;
  Result<std::shared_ptr<RunningJob>> runner =
      RunningJob::Prepare(record, codec::EncodeJobBundle({*job, *scene}), std::nullopt,
                          std::nullopt, {}, {}, {}, {}, agents, reported_rays_per_second);
  EXPECT_TRUE(runner.ok()) << runner.error();
  return runner.ok() ? *runner : nullptr;
}

// Runs `r`'s planned round here and folds it in as if it took `round_seconds`; its rays.
uint64_t RunOneRound(RunningJob& r, double round_seconds) {
  Result<RoundPlan> plan = r.TakePlannedRound();
  EXPECT_TRUE(plan.ok()) << plan.error();
  const uint64_t rays = plan->rays;
  const scheduler::CompletedRound round = r.RunLocally(std::move(*plan));
  RoundOutcome outcome = r.Reduce(round, round_seconds, false, {4096, 0});
  EXPECT_TRUE(r.InstallOutcome(outcome));
  return rays;
}

// The master's ETA keeps within the job's budgets as render's does: the rays and seconds still to
// come are at most what the budget leaves (a budgeted job showed the time to convergence).
TEST(RunningJobLocalRoundTest, TheProgressKeepsWithinTheJobsBudget) {
  // After the first round, reported as taking `round_seconds`.
  auto after_first_round = [&](uint64_t max_rays, double max_seconds, double round_seconds) {
    std::shared_ptr<RunningJob> r = SmallBudgetedJob(max_rays, max_seconds);
    const uint64_t rays = RunOneRound(*r, round_seconds);
    return std::pair(r->Progress(scheduler::Clock::now()), rays);
  };
  const auto [free, first_rays] = after_first_round(0, 0, 1.0);
  ASSERT_TRUE(free.seconds_left.has_value());
  ASSERT_GT(free.rays_left, 100'000u);
  // A ray budget of a third of what is left: the rays to come are within it.
  const uint64_t max_rays = first_rays + free.rays_left / 3;
  const auto [rayed, rayed_first] = after_first_round(max_rays, 0, 1.0);
  EXPECT_LT(rayed.rays_left, free.rays_left);
  EXPECT_LE(rayed.rays_left, max_rays - rayed_first);
  EXPECT_GT(rayed.fraction, free.fraction);
  // A time budget of 1.5 s (the rounds' share of it under a second: SolveBudget) after a round of
  // 0.1 s: the ETA is what is left of the share, not the 2 s to convergence.
  const auto [timed, timed_first] = after_first_round(0, 1.5, 0.1);
  ASSERT_TRUE(timed.seconds_left.has_value());
  EXPECT_GT(*timed.seconds_left, 0);
  EXPECT_LE(*timed.seconds_left, 1.5 - 0.1);
  EXPECT_LT(*timed.seconds_left, *free.seconds_left);
}

// A time budget paces the master's rounds as render's: after a round that took most of the
// rounds' share, the next is cut to what fits in the rest at its pace (before, a farm job's time
// budget only stopped the rounds, after however long the last one ran).
TEST(RunningJobLocalRoundTest, ATimeBudgetPacesTheRounds) {
  // The rays of the first round and those planned after it, reported as taking 0.9 s.
  auto after_first_round = [&](double max_seconds) {
    std::shared_ptr<RunningJob> r = SmallBudgetedJob(0, max_seconds);
    const uint64_t first = RunOneRound(*r, 0.9);
    return std::pair(first, r->planned_rays());
  };
  const auto [first, next] = after_first_round(0);
  ASSERT_GT(next, 1000u);
  // 1.5 s: the rounds' share is under a second (SolveBudget), of which the first round took 0.9:
  // at its pace, what is left is under a tenth of its rays.
  const auto [paced_first, paced_next] = after_first_round(1.5);
  EXPECT_EQ(paced_first, first) << "the first round, unmeasured, is not paced";
  EXPECT_GT(paced_next, 0u);
  EXPECT_LT(paced_next, next);
  EXPECT_LE(paced_next, first / 10);
  // A roomy budget leaves the round as it was.
  EXPECT_EQ(after_first_round(1000).second, next);
}

// Before any round has been timed, a time budget's first round is paced at the agents' reported
// speed (half of it: kReportedPaceShare); with none reported, or without a time budget, it is not.
TEST(RunningJobLocalRoundTest, ATimeBudgetsFirstRoundIsPacedAtTheAgentsReportedSpeed) {
  auto first_round = [&](double max_seconds, double reported_rays_per_second) {
    return SmallBudgetedJob(0, max_seconds, 1, reported_rays_per_second)->planned_rays();
  };
  const uint64_t full = first_round(0, 5e4);
  ASSERT_GT(full, 50'000u);
  EXPECT_EQ(first_round(1.5, 0), full) << "no speed reported: not paced";
  EXPECT_EQ(first_round(1000, 5e4), full) << "a roomy budget";
  // 1.5 s, the rounds' share under a second, at half of 50,000 rays/s: under 37,500 rays.
  const uint64_t paced = first_round(1.5, 5e4);
  EXPECT_GT(paced, 0u);
  EXPECT_LT(paced, uint64_t(1.5 * 0.5 * 5e4));
}

}  // namespace
}  // namespace radfarm::daemon
