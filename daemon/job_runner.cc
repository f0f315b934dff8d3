#include "daemon/job_runner.h"

#include <cmath>

#include "codec/patch_scene_codec.h"
#include "core/batch_runner.h"
#include "core/ray_caster.h"
#include "core/solve_control.h"
#include "core/thread_pool.h"
#include "mesh/patch_mesh.h"
#include "protocol/scene_transfer.h"

namespace radfarm::master {
namespace {

constexpr size_t kRecentRounds = 8;

double UnshotPower(const ProgressiveSolver& solver) { return solver.energy().unshot; }

}  // namespace

Result<std::shared_ptr<JobRunner>> JobRunner::Prepare(
    const store::JobRecord& record, const std::vector<uint8_t>& bundle_blob,
    const std::optional<store::Checkpoint>& checkpoint,
    const std::optional<std::vector<uint8_t>>& checkpoint_scene,
    const std::vector<store::RoundRecord>& rounds, const scheduler::SchedulerOptions& options) {
  const std::string job = "job " + std::to_string(record.id);
  Result<codec::JobBundle> bundle = codec::DecodeJobBundle(bundle_blob);
  if (!bundle) return Error{bundle.error()};
  Result<PatchMesh> mesh = PatchMesh::Build(bundle->scene, bundle->job.mesh, nullptr);
  if (!mesh) return Error{mesh.error()};

  std::shared_ptr<JobRunner> runner(new JobRunner());
  runner->record_ = record;
  runner->settings_ = bundle->job.solver;
  if (bundle->job.refine.enabled) {
    Result<RefinementSchedule> schedule =
        RefinementSchedule::Create(bundle->job.refine, *mesh, runner->settings_.shot_rays,
                                   checkpoint ? checkpoint->refine_points : 0);
    if (!schedule) return Error{job + ": " + schedule.error()};
    runner->schedule_.emplace(std::move(*schedule));
  }
  const bool refined_checkpoint = checkpoint && checkpoint->scene_hash;
  if (refined_checkpoint) {
    if (!runner->schedule_) {
      return Error{job + ": its checkpoint names a refined mesh, but refinement is off"};
    }
    if (!checkpoint_scene) {
      return Error{job + ": the refined scene " + *checkpoint->scene_hash + " is missing"};
    }
    if (Status s = runner->RestoreRefinedMesh(*mesh, *checkpoint, *checkpoint_scene); !s) {
      return Error{job + ": " + s.error()};
    }
  } else {
    runner->mesh_ = std::make_unique<PatchMesh>(std::move(*mesh));
    runner->solver_ =
        std::make_unique<ProgressiveSolver>(runner->mesh_->patch_scene(), runner->PhaseSettings());
  }
  if (runner->schedule_ && !checkpoint) {
    // The step SolveRefining takes before round 0. A pool of one runs inline, on this thread.
    const RayCaster caster(runner->mesh_->patch_scene());
    ThreadPool pool(1);
    std::optional<RefinementStep> step =
        runner->schedule_->BeforeFirstRound(*runner->mesh_, *runner->solver_, caster, pool);
    if (step) runner->Install(std::move(*step));
  }
  auto blob = runner->refined_blob_ ? runner->refined_blob_
                                    : std::make_shared<const std::vector<uint8_t>>(
                                          codec::EncodePatchScene(runner->mesh_->patch_scene()));
  runner->wire_ = {static_cast<uint64_t>(record.id), runner->settings_, protocol::HashScene(*blob),
                   static_cast<uint32_t>(runner->mesh_->patch_scene().patches.size())};
  runner->scene_blob_ = std::move(blob);
  runner->scheduler_ = scheduler::RoundScheduler(options);

  if (checkpoint) {
    if (checkpoint->radiosity.size() != runner->patch_count()) {
      return Error{job + ": checkpoint of round " + std::to_string(checkpoint->round) + " has " +
                   std::to_string(checkpoint->radiosity.size()) + " patches, the scene " +
                   std::to_string(runner->patch_count())};
    }
    runner->solver_->Restore(checkpoint->rounds_done, checkpoint->radiosity, checkpoint->unshot,
                             checkpoint->energy);
    JobTotals& t = runner->totals_;
    t.round = checkpoint->rounds_done;
    for (const store::RoundRecord& r : rounds) {
      if (r.round > checkpoint->round) break;
      t.rays += r.rays;
      t.escaped_rays += r.escaped_rays;
      t.back_rays += r.back_rays;
      t.seconds += r.duration_seconds;
    }
  }
  runner->totals_.unshot_fraction = runner->solver_->UnshotFraction();
  runner->totals_.gather_rays_left = runner->solver_->PendingGatherRays();

  const JobTotals& t = runner->totals_;
  if (checkpoint && checkpoint->stop_reason) {  // the job's last round: nothing left to run
    runner->stop_reason_ = checkpoint->stop_reason;
    runner->phase_ = Phase::kFinished;
    return runner;
  }
  if (auto stop = StopBeforeRound(*runner->solver_, runner->settings_, t.rays, t.seconds)) {
    runner->stop_reason_ = stop;
    runner->phase_ = Phase::kFinished;
    return runner;
  }
  RoundPlan plan = runner->solver_->PlanRound(options.default_batch_rays,
                                              NextRoundRayCap(runner->settings_, t.rays));
  if (plan.batches.empty()) {
    runner->stop_reason_ = kStopConverged;
    runner->phase_ = Phase::kFinished;
    return runner;
  }
  runner->planned_ = std::move(plan);
  return runner;
}

Status JobRunner::StartPlannedRound(scheduler::TimePoint now) {
  if (!planned_) return Error{"job " + std::to_string(id()) + ": no round planned"};
  Status s = scheduler_.StartRound(std::move(*planned_), now);
  planned_.reset();
  if (s.ok()) {
    phase_ = Phase::kRound;
    round_started_ = now;
  }
  return s;
}

Result<RoundPlan> JobRunner::TakePlannedRound() {
  if (!planned_) return Error{"job " + std::to_string(id()) + ": no round planned"};
  RoundPlan plan = std::move(*planned_);
  planned_.reset();
  phase_ = Phase::kReducing;
  return plan;
}

scheduler::CompletedRound JobRunner::RunLocally(RoundPlan plan) {
  if (!local_caster_) local_caster_ = std::make_unique<RayCaster>(mesh_->patch_scene());
  BatchRunner runner(mesh_->patch_scene(), *local_caster_, solver_->sampler());
  scheduler::CompletedRound round;
  round.results.reserve(plan.batches.size());
  for (const Batch& b : plan.batches) round.results.push_back(runner.Run(b));
  round.plan = std::move(plan);
  return round;
}

Result<scheduler::CompletedRound> JobRunner::TakeRound() {
  Result<scheduler::CompletedRound> done = scheduler_.TakeCompletedRound();
  if (done.ok()) phase_ = Phase::kReducing;
  return done;
}

RoundOutcome JobRunner::Reduce(const scheduler::CompletedRound& round, double round_seconds,
                               bool checkpoint_due, uint32_t batch_rays) {
  RoundOutcome out;
  uint64_t escaped = 0, back = 0;
  for (const BatchResult& r : round.results) {
    escaped += r.escaped_rays;
    back += r.back_rays;
  }
  solver_->ApplyRound(round.plan, round.results);
  JobTotals& t = totals_;
  t.round = solver_->rounds_done();
  t.rays += round.plan.rays;
  t.escaped_rays += escaped;
  t.back_rays += back;
  t.seconds += round_seconds;
  t.unshot_fraction = solver_->UnshotFraction();
  t.gather_rays_left = solver_->PendingGatherRays();
  recent_.push_back({round.plan.rays, round_seconds});
  if (recent_.size() > kRecentRounds) recent_.erase(recent_.begin());

  out.record = {id(),
                round.plan.round,
                static_cast<uint32_t>(round.plan.shots.size()),
                round.plan.rays,
                t.unshot_fraction,
                UnshotPower(*solver_),
                round_seconds,
                escaped,
                back};
  out.stop = StopAfterRound(round.plan, *solver_, settings_);
  // Refinement between the rounds, as SolveRefining: only when the job goes on.
  if (!out.stop && schedule_ && schedule_->PointPassed(*solver_)) {
    const RayCaster caster(mesh_->patch_scene());
    ThreadPool pool(1);
    std::optional<RefinementStep> step = schedule_->AfterRound(*mesh_, *solver_, caster, pool);
    if (step) {
      Install(std::move(*step));
      out.new_scene = refined_blob_;
      out.new_scene_hash = protocol::HashScene(*refined_blob_);
      out.new_patch_count = static_cast<uint32_t>(mesh_->patch_scene().patches.size());
      t.unshot_fraction = solver_->UnshotFraction();
      t.gather_rays_left = solver_->PendingGatherRays();
    }
  }
  if (!out.stop) out.stop = StopBeforeRound(*solver_, settings_, t.rays, t.seconds);
  if (!out.stop) {
    RoundPlan next = solver_->PlanRound(batch_rays, NextRoundRayCap(settings_, t.rays));
    if (next.batches.empty()) {
      out.stop = kStopConverged;
    } else {
      out.next = std::move(next);
    }
  }
  out.checkpoint_due = checkpoint_due || out.stop.has_value();
  if (out.checkpoint_due) {
    out.checkpoint.job = id();
    out.checkpoint.round = round.plan.round;
    out.checkpoint.rounds_done = solver_->rounds_done();
    out.checkpoint.radiosity = solver_->radiosity();
    out.checkpoint.unshot = solver_->unshot();
    out.checkpoint.energy = solver_->energy();
    if (refined_blob_) {
      out.checkpoint.scene_hash = refined_hash_;
      if (refined_unsaved_) out.checkpoint_scene = refined_blob_;
      refined_unsaved_ = false;
    }
    if (schedule_) out.checkpoint.refine_points = static_cast<uint32_t>(schedule_->next_point());
    out.checkpoint.stop_reason = out.stop;
  }
  return out;
}

SolverSettings JobRunner::PhaseSettings() const {
  return schedule_ ? schedule_->SolverSettingsNow(settings_, mesh_->patch_scene().patches.size())
                   : settings_;
}

void JobRunner::Install(RefinementStep step) {
  local_caster_.reset();
  solver_.reset();  // it refers to the old mesh's scene
  mesh_ = std::make_unique<PatchMesh>(std::move(step.mesh));
  solver_ = std::make_unique<ProgressiveSolver>(mesh_->patch_scene(), PhaseSettings());
  RestoreStep(step, *solver_);
  refined_blob_ =
      std::make_shared<const std::vector<uint8_t>>(codec::EncodePatchScene(mesh_->patch_scene()));
  refined_hash_ = protocol::HashToHex(protocol::HashScene(*refined_blob_));
  refined_unsaved_ = true;
}

// The refined mesh of a checkpoint, rebuilt from its scene blob on the bundle's mesh. It must
// encode to the very bytes stored: agents trace the blob, the solver the rebuilt mesh.
Status JobRunner::RestoreRefinedMesh(const PatchMesh& initial, const store::Checkpoint& checkpoint,
                                     const std::vector<uint8_t>& blob) {
  const std::string& hash = *checkpoint.scene_hash;
  if (protocol::HashToHex(protocol::HashScene(blob)) != hash) {
    return Error{"the refined scene stored under " + hash + " has another hash"};
  }
  Result<PatchScene> scene = codec::DecodePatchScene(blob);
  if (!scene) return Error{"the refined scene " + hash + ": " + scene.error()};
  local_caster_.reset();
  mesh_ = std::make_unique<PatchMesh>(initial.Rebuilt(PatchMesh::PiecesOf(*scene)));
  auto encoded =
      std::make_shared<const std::vector<uint8_t>>(codec::EncodePatchScene(mesh_->patch_scene()));
  if (*encoded != blob) {
    return Error{"the refined scene " + hash + " does not rebuild into the same elements (" +
                 std::to_string(scene->patches.size()) + " stored, " +
                 std::to_string(mesh_->patch_scene().patches.size()) + " rebuilt)"};
  }
  solver_ = std::make_unique<ProgressiveSolver>(mesh_->patch_scene(), PhaseSettings());
  refined_blob_ = std::move(encoded);
  refined_hash_ = hash;
  return Ok{};
}

bool JobRunner::Resume(RoundOutcome& outcome) {
  if (outcome.new_scene) {
    scene_blob_ = std::move(outcome.new_scene);
    wire_.scene_hash = outcome.new_scene_hash;
    wire_.patch_count = outcome.new_patch_count;
  }
  if (outcome.stop) {
    stop_reason_ = outcome.stop;
    phase_ = Phase::kFinished;
    return false;
  }
  planned_ = std::move(outcome.next);
  phase_ = Phase::kRound;
  return true;
}

double JobRunner::RaysPerSecond() const {
  uint64_t rays = 0;
  double seconds = 0;
  for (const auto& [r, s] : recent_) {
    rays += r;
    seconds += s;
  }
  return seconds > 0 ? double(rays) / seconds : 0;
}

std::optional<double> JobRunner::EtaSeconds() const {
  if (phase_ == Phase::kFinished) return 0.0;
  const double left = EstimateSecondsLeft(totals_.unshot_fraction, settings_.tolerance,
                                          totals_.seconds, totals_.rays, totals_.gather_rays_left);
  if (left < 0 || !std::isfinite(left)) return std::nullopt;
  return left;
}

}  // namespace radfarm::master
