#include "cli/render_state.h"

#include <chrono>

#include "codec/patch_scene_codec.h"
#include "protocol/scene_transfer.h"
#include "store/solve_checkpoint.h"

namespace radfarm {
namespace {

constexpr int kCheckpointsKept = 2;

using Clock = std::chrono::steady_clock;

double Seconds(Clock::duration d) { return std::chrono::duration<double>(d).count(); }

Status Prefixed(Status s) { return s ? s : Status{Error{"--db: " + s.error()}}; }

}  // namespace

Result<RenderState> RenderState::Open(const std::string& db_path, const codec::JobBundle& bundle) {
  codec::JobBundle identity = bundle;
  identity.job.solver.threads = 0;
  const std::vector<uint8_t> blob = codec::EncodeJobBundle(identity);
  const std::string hash = protocol::HashToHex(protocol::HashScene(blob));

  Result<store::JobStore> opened = store::JobStore::Open(db_path);
  if (!opened) return Error{"--db: " + opened.error()};
  RenderState state(std::move(*opened));
  store::JobStore& s = *state.store_;

  Result<std::vector<store::JobRecord>> jobs = s.ListJobs();
  if (!jobs) return Error{"--db: " + jobs.error()};
  std::optional<store::JobRecord> found;
  for (const store::JobRecord& job : *jobs) {
    if (job.spec.scene_hash == hash && job.state != store::JobState::kCancelled &&
        job.state != store::JobState::kFailed) {
      found = job;  // the newest one wins
    }
  }
  if (!found) {
    if (Status st = s.PutScene(hash, blob); !st) return Error{"--db: " + st.error()};
    store::JobSpec spec{bundle.job.scene_path, hash, "{}", bundle.job.solver.seed, 0};
    Result<store::JobId> id = s.SubmitJob(spec);
    if (!id) return Error{"--db: " + id.error()};
    if (Status st = s.SetJobState(*id, store::JobState::kRunning); !st) {
      return Error{"--db: " + st.error()};
    }
    state.job_ = *id;
    return state;
  }
  state.job_ = found->id;
  if (found->state == store::JobState::kQueued || found->state == store::JobState::kPaused) {
    if (Status st = s.SetJobState(found->id, store::JobState::kRunning); !st) {
      return Error{"--db: " + st.error()};
    }
  }
  Result<std::optional<store::Checkpoint>> checkpoint = s.LoadLatestCheckpoint(found->id);
  if (!checkpoint) return Error{"--db: " + checkpoint.error()};
  if (!*checkpoint) return state;
  Result<std::vector<store::RoundRecord>> rounds = s.ListRounds(found->id);
  if (!rounds) return Error{"--db: " + rounds.error()};
  const store::Checkpoint& c = **checkpoint;
  if (c.scene_hash) {
    Result<std::optional<std::vector<uint8_t>>> blob = s.GetScene(*c.scene_hash);
    if (!blob) return Error{"--db: " + blob.error()};
    if (!*blob) return Error{"--db: the refined scene " + *c.scene_hash + " is missing"};
    Result<PatchScene> scene = codec::DecodePatchScene(**blob);
    if (!scene) return Error{"--db: the refined scene " + *c.scene_hash + ": " + scene.error()};
    state.resume_scene_ = std::make_unique<PatchScene>(std::move(*scene));
    state.scene_hash_ = c.scene_hash;
  }
  auto resume =
      std::make_unique<SolveState>(store::ResumeStateOf(c, *rounds, state.resume_scene_.get()));
  state.last_ = resume->totals;
  state.resume_ = std::move(resume);
  return state;
}

Status RenderState::SaveRound(const SolveState& now) {
  const auto start = Clock::now();
  if (!writer_) writer_ = std::make_unique<CheckpointWriter>(*store_);
  if (now.refined_scene == nullptr) {
    scene_hash_.reset();
  } else if (!scene_hash_ || now.refinements != scene_refinements_) {
    auto blob =
        std::make_shared<const std::vector<uint8_t>>(codec::EncodePatchScene(*now.refined_scene));
    const std::string hash = protocol::HashToHex(protocol::HashScene(*blob));
    RADFARM_RETURN_IF_ERROR(writer_->Submit(
        [hash, blob](store::JobStore& s) { return Prefixed(s.PutScene(hash, *blob)); }, false));
    scene_hash_ = hash;
    scene_refinements_ = now.refinements;
  }
  const double unshot_fraction =
      now.energy.emitted > 0 ? now.energy.unshot / now.energy.emitted : 0;
  const store::RoundRecord round{job_,
                                 now.round,
                                 now.shooters,
                                 now.totals.rays - last_.rays,
                                 unshot_fraction,
                                 now.energy.unshot,
                                 now.totals.seconds - last_.seconds,
                                 now.totals.escaped_rays - last_.escaped_rays,
                                 now.totals.backface_hits - last_.backface_hits};
  last_ = now.totals;
  {
    std::lock_guard<std::mutex> lock(reports_->mu);
    for (double seconds : reports_->written_seconds) pacer_.Written(job_, seconds);
    reports_->written_seconds.clear();
  }
  const auto now_ms = static_cast<uint64_t>(
      std::chrono::duration_cast<std::chrono::milliseconds>(start.time_since_epoch()).count());
  if (writer_->checkpoint_pending() || !pacer_.Due(job_, now_ms)) {
    // The round's row now (resumed totals count rows); its state for Finish, in case it is the
    // last. Assigning reuses the buffers of the round left out before.
    unsaved_ = true;
    unsaved_state_ = now;
    unsaved_round_ = round;
    unsaved_scene_hash_ = scene_hash_;
    return writer_->Submit([round](store::JobStore& s) { return Prefixed(s.RecordRound(round)); },
                           false);
  }
  unsaved_ = false;
  store::Checkpoint checkpoint = store::CheckpointOf(job_, now, scene_hash_);
  return QueueCheckpoint(round, std::move(checkpoint), Seconds(Clock::now() - start));
}

Status RenderState::QueueCheckpoint(const store::RoundRecord& round, store::Checkpoint checkpoint,
                                    double waited_seconds) {
  auto shared = std::make_shared<const store::Checkpoint>(std::move(checkpoint));
  return writer_->Submit(
      [round, shared, waited_seconds, job = job_,
       reports = reports_](store::JobStore& s) -> Status {
        const auto start = Clock::now();
        Report report{round.round, {}, 0, waited_seconds};
        RADFARM_RETURN_IF_ERROR(Prefixed(s.SaveCheckpoint(round, *shared, &report.cost)));
        RADFARM_RETURN_IF_ERROR(Prefixed(s.PruneCheckpoints(job, kCheckpointsKept)));
        report.seconds = Seconds(Clock::now() - start);
        std::lock_guard<std::mutex> lock(reports->mu);
        reports->done.push_back(report);
        reports->written_seconds.push_back(report.seconds);
        return Status{Ok{}};
      },
      true);
}

std::vector<RenderState::Report> RenderState::TakeReports() {
  std::lock_guard<std::mutex> lock(reports_->mu);
  return std::exchange(reports_->done, {});
}

Status RenderState::Finish() {
  if (writer_) {
    Status written = writer_->Drain();
    if (written && unsaved_) {
      const auto start = Clock::now();
      store::Checkpoint checkpoint =
          store::CheckpointOf(job_, std::move(unsaved_state_), unsaved_scene_hash_);
      unsaved_ = false;
      written = QueueCheckpoint(unsaved_round_, std::move(checkpoint), 0);
      if (written) written = writer_->Drain();
      // Here the render waits for all of it.
      std::lock_guard<std::mutex> lock(reports_->mu);
      if (!reports_->done.empty()) {
        reports_->done.back().waited_seconds = Seconds(Clock::now() - start);
      }
    }
    writer_.reset();
    RADFARM_RETURN_IF_ERROR(written);
  }
  Result<std::optional<store::JobRecord>> job = store_->GetJob(job_);
  if (!job) return Error{"--db: " + job.error()};
  if (*job && (*job)->state == store::JobState::kRunning) {
    if (Status s = store_->SetJobState(job_, store::JobState::kDone); !s) {
      return Error{"--db: " + s.error()};
    }
  }
  return Ok{};
}

}  // namespace radfarm
