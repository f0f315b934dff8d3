// RunningJob::RunLocally: a job whose every round the master computes itself ends with the
// radiosity `radfarm render` gives, to the bit (core/batch.h: a batch's result does not depend on
// where it runs).
#include <gtest/gtest.h>

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

}  // namespace
}  // namespace radfarm::daemon
