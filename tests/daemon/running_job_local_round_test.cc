// RunningJob::RunLocally: a job whose every round the master computes itself ends with the
// radiosity `radfarm render` gives, to the bit (core/batch.h: a batch's result does not depend on
// where it runs). And RunningJob::Prepare plans the first round tapered for the agents known.
#include <gtest/gtest.h>

#include <algorithm>

#include "codec/job_bundle.h"
#include "daemon/running_job.h"
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

}  // namespace
}  // namespace radfarm::daemon
