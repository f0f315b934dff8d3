#include "cli/render_state.h"

#include "codec/patch_scene_codec.h"
#include "protocol/scene_transfer.h"
#include "store/solve_checkpoint.h"

namespace radfarm {
namespace {

constexpr int kCheckpointsKept = 2;

}  // namespace

Result<RenderState> RenderState::Open(const std::string& db_path, const codec::JobBundle& bundle) {
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
  if (now.refined_scene == nullptr) {
    scene_hash_.reset();
  } else if (!scene_hash_ || now.refinements != scene_refinements_) {
    const std::vector<uint8_t> blob = codec::EncodePatchScene(*now.refined_scene);
    const std::string hash = protocol::HashToHex(protocol::HashScene(blob));
    if (Status s = store_.PutScene(hash, blob); !s) return Error{"--db: " + s.error()};
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
  const store::Checkpoint checkpoint = store::CheckpointOf(job_, now, scene_hash_);
  if (Status s = store_.SaveCheckpoint(round, checkpoint); !s) return Error{"--db: " + s.error()};
  if (Status s = store_.PruneCheckpoints(job_, kCheckpointsKept); !s) {
    return Error{"--db: " + s.error()};
  }
  last_ = now.totals;
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
