#include "cli/render_state.h"

#include "protocol/scene_transfer.h"

namespace radfarm {
namespace {

constexpr int kCheckpointsKept = 2;

}  // namespace

Result<RenderState> RenderState::Open(const std::string& db_path,
                                      const codec::JobBundle& bundle) {
  codec::JobBundle identity = bundle;
  identity.job.solver.threads = 0;
  const std::vector<uint8_t> blob = codec::EncodeJobBundle(identity);
  const std::string hash = protocol::HashToHex(protocol::HashScene(blob));

  Result<store::JobStore> opened = store::JobStore::Open(db_path);
  if (!opened) return Error{"--db: " + opened.error()};
  RenderState state(std::move(*opened));
  store::JobStore& s = state.store_;

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
  SolveCheckpoint resume{c.round, c.rounds_done, c.radiosity, c.unshot, c.energy, 0, 0, 0, 0};
  for (const store::RoundRecord& r : *rounds) {
    if (r.round > c.round) break;
    resume.rays += r.rays;
    resume.escaped_rays += r.escaped_rays;
    resume.backface_hits += r.back_rays;
    resume.seconds += r.duration_seconds;
  }
  state.last_ = resume;
  state.resume_ = std::move(resume);
  return state;
}

Status RenderState::SaveRound(const SolveCheckpoint& now) {
  const double unshot_fraction = now.energy.emitted > 0 ? now.energy.unshot / now.energy.emitted : 0;
  const store::RoundRecord round{job_,
                                 now.round,
                                 now.shooters,
                                 now.rays - last_.rays,
                                 unshot_fraction,
                                 now.energy.unshot,
                                 now.seconds - last_.seconds,
                                 now.escaped_rays - last_.escaped_rays,
                                 now.backface_hits - last_.backface_hits};
  const store::Checkpoint checkpoint{job_,         now.round, now.rounds_done, now.radiosity,
                                     now.unshot,   now.energy, 0};
  if (Status s = store_.SaveCheckpoint(round, checkpoint); !s) return Error{"--db: " + s.error()};
  if (Status s = store_.PruneCheckpoints(job_, kCheckpointsKept); !s) {
    return Error{"--db: " + s.error()};
  }
  last_ = now;
  return Ok{};
}

Status RenderState::Finish() {
  Result<std::optional<store::JobRecord>> job = store_.GetJob(job_);
  if (!job) return Error{"--db: " + job.error()};
  if (*job && (*job)->state == store::JobState::kRunning) {
    if (Status s = store_.SetJobState(job_, store::JobState::kDone); !s) {
      return Error{"--db: " + s.error()};
    }
  }
  return Ok{};
}

}  // namespace radfarm
