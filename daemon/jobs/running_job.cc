#include "daemon/jobs/running_job.h"

#include <malloc.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "base/cpu_clock.h"
#include "base/result.h"
#include "codec/patch_scene_codec.h"
#include "core/batch_tracer.h"
#include "core/solve_control.h"
#include "core/solve_rules.h"
#include "mesh/patch_mesh.h"
#include "protocol/scene_transfer.h"
#include "solve/local_solve.h"
#include "store/solve_checkpoint.h"

namespace radfarm::daemon {
namespace {

// The share of the agents' reported rays/s a time budget's first round is planned at: they report
// their tracing alone, and a round also pays the wire, the master's fold and its tail (render
// plans its first round at half its sample's pace for the same reason).
constexpr double kReportedPaceShare = 0.5;

constexpr size_t kRecentRounds = 8;
// Accepted results sent to the worker together: one hand-over per few dozen batches.
constexpr size_t kFoldChunk = 32;
// Above this many patches a refining job's ray caster, built to verify batches, is released when
// the round's reduction starts rather than kept for the job (docs/MEMORY.md).
constexpr size_t kKeepCasterPatches = 100000;

// The refined scene `checkpoint` names: its stored blob, checked against the hash, decoded.
Result<PatchScene> RefinedSceneOf(const store::Checkpoint& checkpoint, const RefineSettings& refine,
                                  const std::optional<std::vector<uint8_t>>& blob) {
  const std::string& hash = *checkpoint.scene_hash;
  if (!refine.enabled) return Error{"its checkpoint names a refined mesh, but refinement is off"};
  if (!blob) return Error{"the refined scene " + hash + " is missing"};
  if (protocol::HashToHex(protocol::HashScene(*blob)) != hash) {
    return Error{"the refined scene stored under " + hash + " has another hash"};
  }
  Result<PatchScene> scene = codec::DecodePatchScene(*blob);
  if (!scene) return Error{"the refined scene " + hash + ": " + scene.error()};
  return scene;
}

// The scene agents fetch, packed once, straight from the encoder's buffer: the uncompressed blob
// is never copied or kept.
std::shared_ptr<const protocol::PackedScene> PackPatchScene(const PatchScene& scene) {
  std::shared_ptr<const protocol::PackedScene> packed;
  codec::EncodePatchScene(scene, [&](std::span<const uint8_t> blob) {
    packed = std::make_shared<const protocol::PackedScene>(protocol::PackScene(blob));
  });
  return packed;
}

// The same rays of the same shooter. (A kept result's round is the round it was folded in,
// matched first; a gather batch's own key is kGatherRound, core/batch.h.)
bool SameRays(const Batch& a, const Batch& b) {
  return a.shooter == b.shooter && a.first_ray == b.first_ray && a.ray_count == b.ray_count;
}

}  // namespace

Result<std::shared_ptr<RunningJob>> RunningJob::Prepare(
    const store::JobRecord& record, const std::vector<uint8_t>& bundle_blob,
    const std::optional<store::Checkpoint>& checkpoint,
    const std::optional<std::vector<uint8_t>>& checkpoint_scene,
    const std::vector<store::RoundRecord>& rounds, const scheduler::SchedulerOptions& options,
    std::vector<store::StoredBatchResult> stored, SubmittedMesh meshed, size_t agents,
    double agents_rays_per_second, StartLightSource start, LightScoreSource scores) {
  const std::string job = "job " + std::to_string(record.id);
  // The whole process's CPU: the start's direct light runs on a pool of its own.
  LapClock lap;
  JobTimeline timeline;
  auto spent_on = [&](JobPhase phase) {
    const Spent s = lap.Lap();
    AddToTimeline(&timeline, phase, kRanOnMaster, s.wall_seconds, s.cpu_seconds);
  };
  Result<codec::JobBundle> bundle = codec::DecodeJobBundle(bundle_blob);
  RADFARM_RETURN_IF_ERROR(bundle);
  // The job file's threads are the submitting machine's choice: the master's work (the start's
  // direct light, refinement) runs on the master's cores. The bits do not depend on the count.
  bundle->job.solver.threads = 0;
  const bool meshed_at_submission = !meshed.empty();
  if (meshed_at_submission) {
    AddToTimeline(&timeline, JobPhase::kMeshing, kRanOnMaster, meshed.meshing.wall_seconds,
                  meshed.meshing.cpu_seconds);
  }
  // The patches alone when that is all the submission kept (a job without refinement); else the
  // mesh, as submitted or built now.
  std::optional<PatchScene> patches;
  std::optional<PatchMesh> mesh;
  if (meshed.patches && !bundle->job.refine.enabled) {
    patches.emplace(std::move(*meshed.patches));
  } else if (meshed.mesh) {
    mesh.emplace(std::move(*meshed.mesh));
  } else {
    Result<PatchMesh> built = PatchMesh::Build(bundle->scene, bundle->job.mesh, nullptr);
    RADFARM_RETURN_IF_ERROR(built);
    mesh.emplace(std::move(*built));
  }
  meshed = {};
  spent_on(JobPhase::kMeshing);

  std::shared_ptr<RunningJob> runner(new RunningJob());
  runner->meshed_at_submission_ = meshed_at_submission;
  runner->record_ = record;
  runner->settings_ = bundle->job.solver;
  runner->estimator_ = ProgressEstimator(runner->settings_.tolerance);
  // A resumed job's estimate starts from the rounds it ran, not from nothing.
  double unshot_before = 1;
  for (const store::RoundRecord& r : rounds) {
    runner->estimator_.AddRound(
        {r.rays, r.duration_seconds, unshot_before, r.unshot_fraction, false});
    unshot_before = r.unshot_fraction;
  }
  runner->reported_pace_ = kReportedPaceShare * std::max(0.0, agents_rays_per_second);
  // The checkpoint as the driver resumes it; a refined mesh's scene checked against its hash.
  std::optional<SolveState> resume;
  std::optional<PatchScene> refined_scene;
  if (checkpoint) {
    const store::Checkpoint& c = *checkpoint;
    if (c.scene_hash) {
      Result<PatchScene> scene = RefinedSceneOf(c, bundle->job.refine, checkpoint_scene);
      if (!scene) return Error{job + ": " + scene.error()};
      refined_scene = std::move(*scene);
    }
    resume = store::ResumeStateOf(c, rounds, refined_scene ? &*refined_scene : nullptr);
  }
  runner->pool_ = std::make_unique<ThreadPool>(1);
  std::shared_ptr<const protocol::PackedScene> packed;
  const SolveState* resume_at = resume ? &*resume : nullptr;
  Result<std::unique_ptr<RoundDriver>> driver = [&]() -> Result<std::unique_ptr<RoundDriver>> {
    if (bundle->job.refine.enabled) {
      return RoundDriver::Start(std::move(*mesh), runner->settings_, bundle->job.refine, resume_at,
                                *runner->pool_, std::move(start), std::move(scores));
    }
    // Without refinement the master needs the patches alone (agents trace, `radfarm fetch` makes
    // the display): the mesh (about 300 bytes a patch) goes first, its pages back to the system,
    // which freeing leaves in the heap. Then the scene is packed before the solver and its ray
    // caster exist, so the encoder's buffer (about 220 bytes a patch) is not added to theirs.
    if (!patches) {
      patches.emplace(std::move(*mesh).TakePatchScene());
      mesh.reset();
      malloc_trim(0);
    }
    packed = PackPatchScene(*patches);
    return RoundDriver::StartOwning(std::move(*patches), runner->settings_, resume_at,
                                    std::move(start));
  }();
  if (!driver) return Error{job + ": " + driver.error()};
  runner->driver_ = std::move(*driver);
  spent_on(JobPhase::kDirectLight);  // the solver's start (and, packed before it, the scene)
  if (refined_scene) {
    // Agents trace the stored blob, the solver the rebuilt mesh: they must be the same elements.
    auto encoded = std::make_shared<const std::vector<uint8_t>>(
        codec::EncodePatchScene(runner->driver_->scene()));
    if (*encoded != *checkpoint_scene) {
      return Error{job + ": the refined scene " + *checkpoint->scene_hash +
                   " does not rebuild into the same elements (" +
                   std::to_string(refined_scene->patches.size()) + " stored, " +
                   std::to_string(runner->driver_->scene().patches.size()) + " rebuilt)"};
    }
    runner->refined_blob_ = std::move(encoded);
    runner->refined_packed_ =
        std::make_shared<const protocol::PackedScene>(protocol::PackScene(*runner->refined_blob_));
    runner->refined_hash_ = *checkpoint->scene_hash;
  } else if (runner->driver_->refined()) {
    runner->EncodeRefinedScene();  // the step before round 0
  }
  if (runner->refined_packed_) {
    packed = runner->refined_packed_;
  } else if (!packed) {
    packed = PackPatchScene(runner->driver_->scene());
  }
  spent_on(JobPhase::kMeshing);  // the refined scene encoded, the scene packed
  runner->timeline_ = std::move(timeline);
  runner->round_clock_ = LapClock();
  runner->wire_ = {static_cast<uint64_t>(record.id), runner->settings_, packed->hash,
                   static_cast<uint32_t>(runner->driver_->scene().patches.size())};
  runner->scene_ = std::move(packed);
  runner->scheduler_ = scheduler::RoundScheduler(options);
  runner->UpdateTotals();
  runner->UpdateRules();

  // The round the solver plans next, with the batch size its kept results were planned with.
  runner->stored_ = std::move(stored);
  // No agent is measured yet: a round without kept results gets the default batch size, tapered
  // for the agents known when the job started (untapered, the end of a first round of
  // quarter-second batches leaves most agents idle).
  const BatchSizing sizing =
      runner->SizingFor(runner->driver_->solver().rounds_done(),
                        {options.default_batch_rays, scheduler::TaperWays(options, agents)});
  std::optional<RoundPlan> plan = runner->PlanNext(sizing);
  if (!plan) {
    runner->stop_reason_ = runner->driver_->stop_reason();
    runner->phase_ = Phase::kFinished;
    return runner;
  }
  runner->RestoreResults(*plan, sizing);
  runner->fold_plan_ = std::make_shared<const RoundPlan>(*plan);
  const bool gather_now = plan->gather;
  runner->planned_ = std::move(*plan);
  runner->planned_sizing_ = sizing;
  runner->options_ = options;
  // With no agent known yet the gather round would be planned untapered: then after round 0,
  // with the sizing the agents' measurements give (Reduce).
  if (!gather_now && agents > 0) runner->PlanGatherAhead(sizing, options);
  return runner;
}

void RunningJob::PlanGatherAhead(BatchSizing sizing, const scheduler::SchedulerOptions& options) {
  ahead_planned_ = true;
  // A budget may cut or drop the gather, and a refinement step replaces the mesh its batches
  // trace: then the batches traced ahead would not be the round's.
  const SolverSettings& s = driver_->settings();
  if (options.gather_ahead_rays == 0 || s.max_rays > 0 || s.max_seconds > 0 || driver_->refines()) {
    return;
  }
  ahead_plan_ = GatherAhead::Plan(driver_->solver(), sizing, options.gather_ahead_rays);
  if (ahead_plan_) ahead_sizing_ = sizing;
}

Status RunningJob::StartGatherAhead(scheduler::TimePoint now, std::span<const uint64_t> agents) {
  if (!ahead_plan_) return Ok{};
  Result<std::unique_ptr<GatherAhead>> ahead =
      GatherAhead::Start(std::move(*ahead_plan_), *ahead_sizing_, options_, now, agents);
  ahead_plan_.reset();
  RADFARM_RETURN_IF_ERROR(ahead);
  ahead_ = std::move(*ahead);
  return Ok{};
}

BatchSizing RunningJob::SizingFor(uint32_t round, BatchSizing fallback) const {
  for (const store::StoredBatchResult& r : stored_) {
    if (r.batch.round == round) return {r.batch_rays, r.taper_ways};
  }
  return fallback;
}

std::optional<RoundPlan> RunningJob::PlanNext(BatchSizing sizing) {
  // Under a time budget a round is trimmed to the time left and paced (RoundDriver::PlanNext) at
  // the recent rounds' pace, as render's are at its rounds'; before a round has been timed, at the
  // agents' reported speed (reported_pace_), and not at all when none has reported one.
  double pace = 0;
  if (driver_->settings().max_seconds > 0)
    pace = recent_.empty() ? reported_pace_ : RaysPerSecond();
  std::optional<RoundPlan> plan = driver_->PlanNext(sizing.batch_rays, totals_.seconds, pace);
  if (plan) TaperBatches(sizing.taper_ways, TaperFloor(sizing.batch_rays), &plan->batches);
  return plan;
}

void RunningJob::RestoreResults(const RoundPlan& plan, BatchSizing sizing) {
  restored_.clear();
  restore_mismatches_ = 0;
  for (store::StoredBatchResult& r : stored_) {
    if (r.batch.round != plan.round) continue;
    if (BatchSizing{r.batch_rays, r.taper_ways} == sizing && r.index < plan.batches.size() &&
        SameRays(plan.batches[r.index], r.batch)) {
      restored_.emplace_back(r.index, std::move(r.result));
    } else {
      ++restore_mismatches_;
    }
  }
  std::erase_if(stored_,
                [&](const store::StoredBatchResult& r) { return r.batch.round <= plan.round; });
}

void RunningJob::LeaseReturnedAheadFirst() {
  if (!ahead_ || !ahead_->adopted() || phase_ != Phase::kRound) return;
  for (uint32_t index : ahead_->TakeReturned()) scheduler_.LeaseFirst(index);
}

Status RunningJob::StartPlannedRound(scheduler::TimePoint now) {
  if (!planned_) return Error{"job " + std::to_string(id()) + ": no round planned"};
  running_rays_ = planned_->rays;
  rays_before_round_ = totals_.rays;
  running_gather_ = planned_->gather;
  running_sizing_ = planned_sizing_;
  running_round_ = planned_->round;
  std::vector<uint32_t> done;
  done.reserve(restored_.size());
  for (const auto& [index, result] : restored_) done.push_back(index);
  std::vector<std::pair<uint32_t, BatchResult>> computed;
  std::vector<uint32_t> in_flight;
  if (ahead_ && planned_->gather) {
    // The gather's round: the batches computed ahead start done (JobRounds accepts them), and
    // those still out are leased last, as their results will likely have come by then.
    GatherAhead::Adopted adopted = ahead_->Adopt(*planned_, done);
    computed = std::move(adopted.results);
    adopted_ = std::move(adopted.agents);
    in_flight = std::move(adopted.in_flight);
  }
  Status s = scheduler_.StartRound(std::move(*planned_), now, done, std::move(computed), in_flight);
  planned_.reset();
  // The restored results are folded in as accepted ones are, first.
  unfolded_ = std::exchange(restored_, {});
  restored_count_ = unfolded_.size();
  if (s.ok()) {
    phase_ = Phase::kRound;
    round_started_ = now;
  }
  return s;
}

Result<RoundPlan> RunningJob::TakePlannedRound() {
  if (!planned_) return Error{"job " + std::to_string(id()) + ": no round planned"};
  RoundPlan plan = std::move(*planned_);
  planned_.reset();
  restored_.clear();                // computed here anyway: cheaper than the hand-over
  if (plan.gather) ahead_.reset();  // likewise
  phase_ = Phase::kReducing;
  running_rays_ = 0;  // computed here: shown from Reduce's result
  return plan;
}

scheduler::CompletedRound RunningJob::RunLocally(RoundPlan plan) {
  scheduler::CompletedRound round;
  round.results = LocalBatches(*pool_).Run(*driver_, plan);
  round.plan = std::move(plan);
  return round;
}

Result<scheduler::CompletedRound> RunningJob::TakeRound() {
  Result<scheduler::CompletedRound> done = scheduler_.TakeCompletedRound();
  if (!done.ok()) return done;
  if (ahead_ && ahead_->adopted()) ahead_.reset();  // the gather round is over
  // Results taken out for folding but not sent yet go back in: Reduce adds them.
  for (auto& [index, result] : unfolded_) done->results[index] = std::move(result);
  unfolded_.clear();
  phase_ = Phase::kReducing;
  return done;
}

std::optional<ResultDigest> RunningJob::DigestOfResult(scheduler::BatchId batch) const {
  const BatchResult* result = scheduler_.PeekResult(batch);
  if (result == nullptr) return std::nullopt;
  return DigestOf(*result);
}

bool RunningJob::QueueFold(scheduler::BatchId batch, std::vector<store::StoredBatchResult>* keep) {
  std::optional<BatchResult> result = scheduler_.TakeResult(batch);
  if (!result) return false;
  if (keep != nullptr) {
    // Kept under the round it is folded in (a gather batch's key is kGatherRound: core/batch.h).
    Batch kept = *scheduler_.FindBatch(batch);
    kept.round = running_round_;
    keep->push_back({scheduler::BatchIndex(batch), running_sizing_.batch_rays,
                     running_sizing_.taper_ways, kept, *result});
  }
  unfolded_.emplace_back(scheduler::BatchIndex(batch), std::move(*result));
  return unfolded_.size() >= kFoldChunk;
}

std::vector<std::pair<uint32_t, BatchResult>> RunningJob::TakeFolds() {
  return std::exchange(unfolded_, {});
}

std::vector<ResultDigest> RunningJob::VerifyBatches(const std::vector<Batch>& batches) {
  BatchTracer tracer(driver_->scene(), driver_->caster(), driver_->solver().sampler());
  std::vector<ResultDigest> digests;
  digests.reserve(batches.size());
  for (const Batch& batch : batches) digests.push_back(DigestOf(tracer.Run(batch)));
  return digests;
}

void RunningJob::Fold(std::vector<std::pair<uint32_t, BatchResult>> results) {
  if (!fold_) fold_ = driver_->Reduction(*fold_plan_);
  for (auto& [index, result] : results) fold_->Add(index, std::move(result));
}

void RunningJob::AddPieceAgentSeconds(JobPhase phase, double seconds) {
  AddToTimeline(&timeline_, phase, kRanOnAgents, 0, seconds);
}

void RunningJob::AddAgentSeconds(bool gather, double seconds) {
  AddToTimeline(&timeline_, gather ? JobPhase::kGather : JobPhase::kRounds, kRanOnAgents, 0,
                seconds);
}

RoundOutcome RunningJob::Reduce(const scheduler::CompletedRound& round, double round_seconds,
                                bool checkpoint_due, BatchSizing sizing) {
  RoundOutcome out;
  out.gather = round.plan.gather;
  const double seconds = totals_.seconds + round_seconds;
  // The round's verifications are done (the barrier). A refining job's caster goes before Apply,
  // whose refinement step builds its own for a new mesh. Any other job keeps it for its rounds:
  // built again each round it cost more time and, in pages freed and filled again, more memory.
  if (driver_->refines() && driver_->scene().patches.size() > kKeepCasterPatches) {
    driver_->ReleaseCaster();
  }
  // The round's results were folded in as they came (or, for a round computed here, come all at
  // once); any the loop thread kept are added now: the reduction refuses the ones it has.
  if (!fold_) fold_ = driver_->Reduction(*fold_plan_);
  for (size_t k = 0; k < round.results.size(); ++k) fold_->Add(k, round.results[k]);
  const AppliedRound applied = driver_->Apply(*fold_plan_, *fold_, seconds);
  out.results_held_peak = fold_->peak_held();
  fold_.reset();
  recent_.push_back({round.plan.rays, round_seconds});
  estimator_.AddRound({round.plan.rays, round_seconds, totals_.unshot_fraction,
                       applied.unshot_fraction, round.plan.gather});
  if (recent_.size() > kRecentRounds) recent_.erase(recent_.begin());
  out.record = {id(),
                round.plan.round,
                static_cast<uint32_t>(round.plan.shots.size()),
                round.plan.rays,
                applied.unshot_fraction,
                applied.unshot_power,
                round_seconds,
                applied.escaped_rays,
                applied.back_rays};
  if (applied.refined) {
    UpdateRules();
    EncodeRefinedScene();
    out.new_scene = refined_packed_;
    out.new_scene_hash = refined_packed_->hash;
    out.new_patch_count = static_cast<uint32_t>(driver_->scene().patches.size());
  }
  UpdateTotals();
  // A restarted master replays the rounds it kept results of with the batch sizes they had.
  // The gather round is planned with the batch sizes of the batches traced ahead.
  const BatchSizing next_sizing =
      SizingFor(driver_->solver().rounds_done(),
                ahead_sizing_ && driver_->solver().GatherNext() ? *ahead_sizing_ : sizing);
  if (std::optional<RoundPlan> next = PlanNext(next_sizing)) {
    if (!ahead_planned_ && !next->gather) PlanGatherAhead(next_sizing, options_);
    RestoreResults(*next, next_sizing);
    fold_plan_ = std::make_shared<const RoundPlan>(*next);  // the worker's copy, for the fold
    out.next = std::move(*next);
    out.next_sizing = next_sizing;
  } else {
    out.stop = driver_->stop_reason();
    stored_.clear();
  }
  out.checkpoint_due = checkpoint_due || out.stop.has_value();
  if (out.checkpoint_due) {
    std::optional<std::string> scene_hash;
    if (refined_blob_) {
      scene_hash = refined_hash_;
      if (refined_unsaved_) out.checkpoint_scene = refined_blob_;
      refined_unsaved_ = false;
    }
    const auto copy_start = std::chrono::steady_clock::now();
    out.checkpoint = store::CheckpointOf(id(), driver_->State(), std::move(scene_hash));
    out.checkpoint_copy_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - copy_start).count();
  }
  return out;
}

void RunningJob::UpdateTotals() {
  const SolveTotals& spent = driver_->totals();
  const ProgressiveSolver& solver = driver_->solver();
  totals_.round = solver.rounds_done();
  totals_.rays = spent.rays;
  totals_.escaped_rays = spent.escaped_rays;
  totals_.back_rays = spent.backface_hits;
  totals_.seconds = spent.seconds;
  totals_.unshot_fraction = solver.UnshotFraction();
  totals_.gather_rays_left = solver.PendingGatherRays();
}

void RunningJob::UpdateRules() {
  rules_ = {DirectStartRule(driver_->scene(), settings_).why,
            DisplayRule(driver_->scene(), settings_).why};
}

void RunningJob::EncodeRefinedScene() {
  refined_blob_ =
      std::make_shared<const std::vector<uint8_t>>(codec::EncodePatchScene(driver_->scene()));
  refined_packed_ =
      std::make_shared<const protocol::PackedScene>(protocol::PackScene(*refined_blob_));
  refined_hash_ = protocol::HashToHex(refined_packed_->hash);
  refined_unsaved_ = true;
}

bool RunningJob::InstallOutcome(RoundOutcome& outcome) {
  const Spent spent = round_clock_.Lap();
  AddToTimeline(&timeline_, outcome.gather ? JobPhase::kGather : JobPhase::kRounds, kRanOnMaster,
                spent.wall_seconds, spent.cpu_seconds);
  if (outcome.new_scene) {
    scene_ = std::move(outcome.new_scene);
    wire_.scene_hash = outcome.new_scene_hash;
    wire_.patch_count = outcome.new_patch_count;
  }
  if (outcome.stop) {
    stop_reason_ = outcome.stop;
    phase_ = Phase::kFinished;
    return false;
  }
  planned_ = std::move(outcome.next);
  planned_sizing_ = outcome.next_sizing;
  phase_ = Phase::kRound;
  return true;
}

double RunningJob::RaysPerSecond() const {
  uint64_t rays = 0;
  double seconds = 0;
  for (const auto& [r, s] : recent_) {
    rays += r;
    seconds += s;
  }
  return seconds > 0 ? double(rays) / seconds : 0;
}

uint64_t RunningJob::RunningRaysDone(scheduler::TimePoint now) const {
  if (phase_ != Phase::kRound) return 0;
  const scheduler::SchedulerCounters counters = scheduler_.counters(now);
  if (!counters.round_active || counters.batches == 0) return 0;
  return running_rays_ * counters.batches_done / counters.batches;
}

uint64_t RunningJob::RaysShown(scheduler::TimePoint now) const {
  switch (phase_) {
    case Phase::kRound:
      if (scheduler_.counters(now).round_active) return rays_before_round_ + RunningRaysDone(now);
      break;
    case Phase::kReducing:
      if (running_rays_ > 0) return rays_before_round_ + running_rays_;  // leased, not local
      break;
    case Phase::kFinished:
      break;
  }
  return totals_.rays;
}

double RunningJob::RaysPerSecond(scheduler::TimePoint now) const {
  uint64_t rays = RunningRaysDone(now);
  double seconds = rays > 0 ? std::chrono::duration<double>(now - round_started_).count() : 0;
  for (const auto& [r, s] : recent_) {
    rays += r;
    seconds += s;
  }
  return seconds > 0 ? double(rays) / seconds : 0;
}

ProgressEstimate RunningJob::Progress(scheduler::TimePoint now) const {
  if (phase_ == Phase::kFinished) return {1.0, 0.0, 0};
  if (phase_ == Phase::kReducing) return last_progress_;
  SolvePosition at{totals_.rays, totals_.unshot_fraction, totals_.gather_rays_left};
  const scheduler::SchedulerCounters counters = scheduler_.counters(now);
  if (counters.round_active && counters.batches > 0) {
    at.round_rays = running_rays_;
    at.round_rays_done = RunningRaysDone(now);
    at.round_seconds = std::chrono::duration<double>(now - round_started_).count();
    at.round_gather = running_gather_;
  }
  // The job's budgets end it where the rounds to convergence would run past them: so does the ETA.
  at.budget_rays_left = driver_->BudgetRaysLeft();
  if (at.budget_rays_left) {
    *at.budget_rays_left -= std::min(*at.budget_rays_left, at.round_rays_done);
  }
  at.budget_seconds_left = driver_->BudgetSecondsLeft(totals_.seconds + at.round_seconds);
  at.display_rays = driver_->display_rays_forecast();
  last_progress_ = estimator_.Estimate(at);
  return last_progress_;
}

}  // namespace radfarm::daemon
