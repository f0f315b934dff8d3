// RunningJob::Prepare with adaptive refinement: a fresh job refines before round 0 exactly as the
// local solve does (same scene blob), a checkpoint on a refined mesh resumes on it, and every way
// a checkpoint's refined mesh can be wrong fails the job with a message naming it.
#include "daemon/jobs/running_job.h"

#include <gtest/gtest.h>

#include "codec/job_bundle.h"
#include "codec/patch_scene_codec.h"
#include "core/ray_caster.h"
#include "core/thread_pool.h"
#include "input/input_scene.h"
#include "job/job.h"
#include "mesh/refinement_schedule.h"
#include "protocol/scene_transfer.h"

namespace radfarm::daemon {
namespace {

codec::JobBundle AdaptiveBundle() {
  Result<Job> job = LoadJob(RADFARM_SOURCE_DIR "/scenes/cornell-box-adaptive.toml");
  EXPECT_TRUE(job.ok()) << job.error();
  Result<InputScene> scene = LoadObjScene(job->scene_path);
  EXPECT_TRUE(scene.ok()) << scene.error();
  job->mesh.patch_size = 50;  // pinned: the shipped job file may change
  return {*job, *scene};
}

// The mesh SolveRefining has before round 0, made with RefinementSchedule as the local solve does.
std::vector<uint8_t> LocallyRefinedBlob(const codec::JobBundle& bundle) {
  Result<PatchMesh> mesh = PatchMesh::Build(bundle.scene, bundle.job.mesh, nullptr);
  EXPECT_TRUE(mesh.ok());
  Result<RefinementSchedule> schedule =
      RefinementSchedule::Create(bundle.job.refine, *mesh, bundle.job.solver.shot_rays);
  EXPECT_TRUE(schedule.ok());
  const ProgressiveSolver solver(
      mesh->patch_scene(),
      schedule->SolverSettingsNow(bundle.job.solver, mesh->patch_scene().patches.size()));
  const RayCaster caster(mesh->patch_scene());
  ThreadPool pool(2);
  std::optional<RefinementStep> step = schedule->BeforeFirstRound(*mesh, solver, caster, pool);
  EXPECT_TRUE(step.has_value()) << "the adaptive Cornell box splits before round 0";
  return step ? codec::EncodePatchScene(step->mesh.patch_scene()) : std::vector<uint8_t>{};
}

// A checkpoint after round 0 on `blob`'s mesh: the initial state of its elements.
store::Checkpoint CheckpointOn(const std::vector<uint8_t>& blob) {
  Result<PatchScene> scene = codec::DecodePatchScene(blob);
  EXPECT_TRUE(scene.ok());
  store::Checkpoint c;
  c.job = 1;
  c.round = 0;
  c.rounds_done = 1;
  for (const Patch& p : scene->patches) {
    c.radiosity.push_back(p.emission);
    c.unshot.push_back(p.emission);
    c.energy.emitted += p.emission.Sum() * p.area;
  }
  c.energy.unshot = c.energy.emitted;
  c.scene_hash = protocol::HashToHex(protocol::HashScene(blob));
  c.refine_points = 1;
  return c;
}

Result<std::shared_ptr<RunningJob>> Prepare(const codec::JobBundle& bundle,
                                            const std::optional<store::Checkpoint>& checkpoint,
                                            const std::optional<std::vector<uint8_t>>& scene) {
  store::JobRecord record;
  record.id = 1;
  return RunningJob::Prepare(record, codec::EncodeJobBundle(bundle), checkpoint, scene, {}, {});
}

TEST(RunningJobRefineTest, AFreshJobRefinesBeforeRoundZeroLikeTheLocalSolve) {
  const codec::JobBundle bundle = AdaptiveBundle();
  const std::vector<uint8_t> local = LocallyRefinedBlob(bundle);
  Result<std::shared_ptr<RunningJob>> runner = Prepare(bundle, std::nullopt, std::nullopt);
  ASSERT_TRUE(runner.ok()) << runner.error();
  EXPECT_TRUE((*runner)->packed_scene()->compressed == protocol::PackScene(local).compressed);
  EXPECT_EQ((*runner)->wire_info().scene_hash, protocol::HashScene(local));
  EXPECT_EQ((*runner)->patch_count(), codec::DecodePatchScene(local)->patches.size());
  Result<PatchMesh> initial = PatchMesh::Build(bundle.scene, bundle.job.mesh, nullptr);
  ASSERT_TRUE(initial.ok());
  EXPECT_GT((*runner)->patch_count(), initial->patch_scene().patches.size());
}

TEST(RunningJobRefineTest, ACheckpointOnARefinedMeshResumesOnIt) {
  const codec::JobBundle bundle = AdaptiveBundle();
  const std::vector<uint8_t> blob = LocallyRefinedBlob(bundle);
  Result<std::shared_ptr<RunningJob>> runner = Prepare(bundle, CheckpointOn(blob), blob);
  ASSERT_TRUE(runner.ok()) << runner.error();
  EXPECT_TRUE((*runner)->packed_scene()->compressed == protocol::PackScene(blob).compressed);
  EXPECT_EQ((*runner)->totals().round, 1u);
  EXPECT_EQ((*runner)->phase(), RunningJob::Phase::kRound);
}

// The checkpoint of the round a job stopped after (a capped round may leave rays of the budget):
// a master restarted before it marked the job done finishes it without another round.
TEST(RunningJobRefineTest, TheLastCheckpointOfAJobRunsNoFurtherRound) {
  const codec::JobBundle bundle = AdaptiveBundle();
  const std::vector<uint8_t> blob = LocallyRefinedBlob(bundle);
  store::Checkpoint last = CheckpointOn(blob);
  last.stop_reason = "ray budget";
  Result<std::shared_ptr<RunningJob>> runner = Prepare(bundle, last, blob);
  ASSERT_TRUE(runner.ok()) << runner.error();
  EXPECT_EQ((*runner)->phase(), RunningJob::Phase::kFinished);
  EXPECT_EQ((*runner)->stop_reason(), std::optional<std::string>("ray budget"));
  // Without the mark the same state goes on (unshot above the tolerance, no ray budget).
  Result<std::shared_ptr<RunningJob>> going_on = Prepare(bundle, CheckpointOn(blob), blob);
  ASSERT_TRUE(going_on.ok()) << going_on.error();
  EXPECT_EQ((*going_on)->phase(), RunningJob::Phase::kRound);
}

TEST(RunningJobRefineTest, AWrongRefinedMeshFailsTheJob) {
  const codec::JobBundle bundle = AdaptiveBundle();
  const std::vector<uint8_t> blob = LocallyRefinedBlob(bundle);
  const store::Checkpoint checkpoint = CheckpointOn(blob);
  const auto expect_error = [](const Result<std::shared_ptr<RunningJob>>& r,
                               const std::string& words) {
    ASSERT_FALSE(r.ok()) << words;
    EXPECT_NE(r.error().find(words), std::string::npos) << r.error();
    EXPECT_NE(r.error().find("job 1"), std::string::npos) << r.error();
  };
  expect_error(Prepare(bundle, checkpoint, std::nullopt), "is missing");

  codec::JobBundle off = bundle;
  off.job.refine = RefineSettings{};
  expect_error(Prepare(off, checkpoint, blob), "refinement is off");

  std::vector<uint8_t> other = blob;
  other[other.size() / 2] ^= 1;
  expect_error(Prepare(bundle, checkpoint, other), "has another hash");

  store::Checkpoint corrupt = checkpoint;
  other.resize(other.size() / 2);
  corrupt.scene_hash = protocol::HashToHex(protocol::HashScene(other));
  expect_error(Prepare(bundle, corrupt, other), "the refined scene " + *corrupt.scene_hash);

  // A scene that decodes but is not what the bundle's mesh rebuilds (the reflectance comes from
  // the bundle's material): agents would trace another scene than the solver's.
  Result<PatchScene> scene = codec::DecodePatchScene(blob);
  ASSERT_TRUE(scene.ok());
  scene->patches[7].reflectance.g *= 0.5;
  const std::vector<uint8_t> foreign = codec::EncodePatchScene(*scene);
  expect_error(Prepare(bundle, CheckpointOn(foreign), foreign),
               "does not rebuild into the same elements");

  store::Checkpoint sizes = checkpoint;
  sizes.radiosity.pop_back();
  sizes.unshot.pop_back();
  expect_error(Prepare(bundle, sizes, blob), "elements, the mesh");

  store::Checkpoint points = checkpoint;
  points.refine_points = 3;
  expect_error(Prepare(bundle, points, blob), "refinement point 3 out of range");
}

}  // namespace
}  // namespace radfarm::daemon
