#include "daemon/job_runner.h"

#include <cmath>

#include "codec/patch_scene_codec.h"
#include "core/solve_control.h"
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
    const std::vector<store::RoundRecord>& rounds, const scheduler::SchedulerOptions& options) {
  Result<codec::JobBundle> bundle = codec::DecodeJobBundle(bundle_blob);
  if (!bundle) return Error{bundle.error()};
  Result<PatchMesh> mesh = PatchMesh::Build(bundle->scene, bundle->job.mesh, nullptr);
  if (!mesh) return Error{mesh.error()};

  std::shared_ptr<JobRunner> runner(new JobRunner());
  runner->record_ = record;
  runner->settings_ = bundle->job.solver;
  runner->scene_ = std::make_unique<PatchScene>(mesh->patch_scene());
  runner->solver_ = std::make_unique<ProgressiveSolver>(*runner->scene_, runner->settings_);
  auto blob = std::make_shared<std::vector<uint8_t>>(codec::EncodePatchScene(*runner->scene_));
  runner->wire_ = {static_cast<uint64_t>(record.id), runner->settings_, protocol::HashScene(*blob),
                   runner->patch_count()};
  runner->scene_blob_ = std::move(blob);
  runner->scheduler_ = scheduler::RoundScheduler(options);

  if (checkpoint) {
    if (checkpoint->radiosity.size() != runner->scene_->patches.size()) {
      return Error{"job " + std::to_string(record.id) + ": checkpoint of round " +
                   std::to_string(checkpoint->round) + " has " +
                   std::to_string(checkpoint->radiosity.size()) + " patches, the scene " +
                   std::to_string(runner->scene_->patches.size())};
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

  const JobTotals& t = runner->totals_;
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
  }
  return out;
}

bool JobRunner::Resume(RoundOutcome& outcome) {
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
  const double left =
      EstimateSecondsLeft(totals_.unshot_fraction, settings_.tolerance, totals_.seconds);
  if (left < 0 || !std::isfinite(left)) return std::nullopt;
  return left;
}

}  // namespace radfarm::master
