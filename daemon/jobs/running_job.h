// RunningJob: one job the master is solving. It owns the job's RoundDriver (solve/round_driver.h:
// the mesh, the solver, the refinement schedule) and its RoundScheduler, and runs the driver's
// rounds with agents in place of `radfarm render`'s threads, so the result is bit-identical to
// `radfarm render` of the same job:
//
//   Prepare (worker thread): decode the bundle, mesh it, start the driver (from the latest
//     checkpoint, on the refined mesh it names, if any), encode the scene blob agents fetch, plan
//     the first round.
//   loop thread: the scheduler leases the round's batches and collects their results; each
//     accepted result goes on to the worker (QueueFold, TakeFolds -> Fold), which folds it into
//     the round (core/round_reduction.h) as it comes, so no round's results are all held.
//   Reduce (worker thread): the driver applies the round (and refines when it passed a
//     refinement point), plans the next one, and the state is copied for the checkpoint the store
//     thread writes meanwhile.
//
// A refinement step gives a new mesh, scene blob (new hash) and solver; InstallOutcome installs
// the blob on the loop thread before the next round's batches are leased, and a round's batch ids
// carry its round, so a result is always validated against the scene of its own round.
//
// Threads: the loop thread owns the job; Reduce runs on a worker while phase() is kReducing,
// and the loop thread leaves the mesh and solver alone until its result comes back. What the loop
// thread reads in any phase (the scene blob, the wire info) changes only in InstallOutcome.
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "base/cpu_clock.h"
#include "base/result.h"
#include "codec/job_bundle.h"
#include "core/job_timeline.h"
#include "core/patch_scene.h"
#include "core/progress_estimator.h"
#include "core/progressive_solver.h"
#include "core/thread_pool.h"
#include "daemon/jobs/batch_verifier.h"
#include "daemon/jobs/gather_ahead.h"
#include "daemon/scheduler/round_scheduler.h"
#include "protocol/batch_convert.h"
#include "protocol/messages.h"
#include "protocol/scene_transfer.h"
#include "solve/round_driver.h"
#include "store/job_store.h"

namespace radfarm::daemon {

// A job's scene as its submission's check meshed it (the same patches: meshing is deterministic).
// A job that refines keeps the mesh; any other keeps its patches alone, the rest of the mesh (about
// 300 bytes a patch) freed before the check built the ray caster of its back-face survey.
struct SubmittedMesh {
  std::shared_ptr<PatchMesh> mesh;
  std::shared_ptr<PatchScene> patches;
  Spent meshing;  // what the check's decoding and meshing cost the master, for the job's timeline
  bool empty() const { return !mesh && !patches; }
};

// What a job has spent so far (restored from its rounds after a restart).
struct JobTotals {
  uint32_t round = 0;  // rounds applied
  uint64_t rays = 0;
  uint64_t escaped_rays = 0;
  uint64_t back_rays = 0;
  double seconds = 0;  // summed round durations
  double unshot_fraction = 1;
  uint64_t gather_rays_left = 0;  // ProgressiveSolver::PendingGatherRays
};

// The result of reducing one round, for the loop thread and the store thread.
struct RoundOutcome {
  store::RoundRecord record;
  store::Checkpoint checkpoint;        // filled when `checkpoint_due`
  double checkpoint_copy_seconds = 0;  // taking it from the solver, on the compute thread
  bool checkpoint_due = false;
  std::optional<std::string> stop;  // the stop reason: the job is done
  std::optional<RoundPlan> next;    // the next round, unless stopping
  // The refined scene's blob, to store (PutScene under checkpoint.scene_hash) before the
  // checkpoint: set on the first checkpoint after a refinement.
  std::shared_ptr<const std::vector<uint8_t>> checkpoint_scene;
  // Set when the round's refinement step split something: the scene agents must trace from the
  // next round on (compressed), its hash and its element count.
  std::shared_ptr<const protocol::PackedScene> new_scene;
  protocol::SceneHash new_scene_hash{};
  uint32_t new_patch_count = 0;
  BatchSizing next_sizing;  // the batch sizes `next` was planned with
  // The most results the fold held at once, waiting for an earlier batch's (RoundReduction):
  // the master's memory for results, which stays small while batches come back in plan order.
  size_t results_held_peak = 0;
  bool gather = false;  // the round was the final gather
};

// What the rules (core/solve_rules.h) gave the job's scene at its size: the direct-light start and
// the display, in words for status.
struct JobRules {
  std::string direct_start;
  std::string display;
};

class RunningJob {
 public:
  enum class Phase { kRound, kReducing, kFinished };

  // Heavy (meshing, refining, planning): call on a worker thread. `checkpoint` and `rounds` come
  // from the store: the job resumes after the checkpoint's round, with the totals of the rounds up
  // to it; `checkpoint_scene` is the blob of the refined scene the checkpoint names (scene_hash).
  // `stored`: accepted results a previous master kept of the rounds after the checkpoint; each of
  // those rounds is planned with their batch size, so the same batches, and the results that
  // match the plan exactly start done (StartPlannedRound). `meshed`, when not empty, is the
  // bundle's scene meshed already with the bundle's settings (at submission): it is used instead
  // of meshing again. `agents`: those known when the job started, for the first round's taper;
  // `agents_rays_per_second`: their last reported speeds summed (0: none measured), the pace of a
  // time budget's first round (kReportedPaceShare of it) until a round has been timed. `start`
  // traces the solver's direct-light starts, a refinement restart's included, and `scores` the
  // refinement steps' light scores (empty: here).
  static Result<std::shared_ptr<RunningJob>> Prepare(
      const store::JobRecord& record, const std::vector<uint8_t>& bundle_blob,
      const std::optional<store::Checkpoint>& checkpoint,
      const std::optional<std::vector<uint8_t>>& checkpoint_scene,
      const std::vector<store::RoundRecord>& rounds, const scheduler::SchedulerOptions& options,
      std::vector<store::StoredBatchResult> stored = {}, SubmittedMesh meshed = {},
      size_t agents = 0, double agents_rays_per_second = 0, StartLightSource start = {},
      LightScoreSource scores = {});

  store::JobId id() const { return record_.id; }
  const store::JobRecord& record() const { return record_; }
  int64_t priority() const { return record_.spec.priority; }
  const SolverSettings& settings() const { return settings_; }
  const protocol::JobWireInfo& wire_info() const { return wire_; }
  // The scene agents fetch, compressed once (protocol/scene_packing.h).
  const std::shared_ptr<const protocol::PackedScene>& packed_scene() const { return scene_; }
  uint32_t patch_count() const { return wire_.patch_count; }
  const RaySampler& sampler() const { return driver_->solver().sampler(); }
  // Loop thread, once kFinished: the direct light the solve started from, one value per patch of
  // its last mesh (ProgressiveSolver::direct_light), or empty; the display starts from it.
  const std::vector<Rgb>& direct_light() const { return driver_->solver().direct_light(); }
  // Loop thread: where the job's time went so far (core/job_timeline.h): Prepare's meshing and
  // start, the agents' compute seconds, and the master's wall and CPU seconds from one round's
  // end to the next's as InstallOutcome takes it back (the whole process's CPU: the loop's work
  // on the results and the compute thread's, every job's together when several run).
  const JobTimeline& timeline() const { return timeline_; }
  JobTimeline TakeTimeline() { return std::move(timeline_); }
  // Loop thread: `seconds` of agents' computing on accepted results of the gather (`gather`) or
  // of a shooting round.
  void AddAgentSeconds(bool gather, double seconds);
  // Loop thread: `seconds` of agents' computing on the pieces of a direct-light start or of a
  // refinement step's light scores, made in `phase`.
  void AddPieceAgentSeconds(JobPhase phase, double seconds);
  bool running_gather() const { return running_gather_; }
  // The rays its display is expected to cast (RoundDriver::display_rays_forecast).
  uint64_t display_rays_forecast() const { return driver_->display_rays_forecast(); }
  const JobTotals& totals() const { return totals_; }
  Phase phase() const { return phase_; }
  // The rules for the job's scene as it stands (Prepare, and again after a refinement step).
  const JobRules& rules() const { return rules_; }
  // Whether Prepare took the mesh built at submission rather than meshing the scene again.
  bool meshed_at_submission() const { return meshed_at_submission_; }
  // Set when Prepare found nothing left to do (the checkpoint already met a stopping rule).
  const std::optional<std::string>& stop_reason() const { return stop_reason_; }
  scheduler::RoundScheduler& scheduler() { return scheduler_; }
  const scheduler::RoundScheduler& scheduler() const { return scheduler_; }
  // Loop thread: the final gather leased ahead of its round (gather_ahead.h); null when there is
  // none (off, no gather, budgets, refinement, or its round has ended). Once its round started
  // (adopted()) it leases nothing more and passes its late results on to the round.
  GatherAhead* gather_ahead() { return ahead_.get(); }
  // Loop thread: every scheduler that leases this job's batches to agents: the round's, then the
  // gather's ahead if any. What happens to an agent (it comes, goes, is blocklisted) happens in
  // all.
  template <class F>
  void ForEachScheduler(F&& f) {
    f(scheduler_);
    if (ahead_) f(ahead_->scheduler());
  }
  // Loop thread: leases the gather ahead (Prepare planned it when the job may: gather on, no ray
  // or time budget, no refinement, options.gather_ahead_rays > 0) to `agents` from now on. Does
  // nothing when none was planned; an error fails the job.
  Status StartGatherAhead(scheduler::TimePoint now, std::span<const uint64_t> agents);
  // Loop thread, after StartPlannedRound: the batches whose results the gather ahead computed
  // (done at the round's start), with their agents, for JobRounds to accept; emptied here.
  std::vector<std::pair<uint32_t, std::string>> TakeAdoptedResults() {
    return std::exchange(adopted_, {});
  }
  // Loop thread, in the gather's round: the batches whose gather-ahead leases ended without a
  // result since the round adopted them go to the front of the round's queue
  // (GatherAhead::TakeReturned). Cheap when there are none; call it before leasing.
  void LeaseReturnedAheadFirst();

  // Loop thread: starts the planned round. Fails if there is none. Results restored from the
  // store start done and are queued for the fold (TakeFolds); the round may be complete at once.
  Status StartPlannedRound(scheduler::TimePoint now);
  // Of the round started last: batches restored from the store; stored results that did not
  // match the plan (and are computed again).
  size_t restored_batches() const { return restored_count_; }
  size_t restore_mismatches() const { return restore_mismatches_; }
  // Loop thread: the rays of the planned round (0 when none is planned).
  uint64_t planned_rays() const { return planned_ ? planned_->rays : 0; }
  // Loop thread: takes the planned round to compute here instead of on agents (RunLocally);
  // phase() becomes kReducing. Fails if none is planned.
  Result<RoundPlan> TakePlannedRound();
  // Worker thread, while kReducing: every batch of `plan` on this thread, as an agent would run
  // it (core/batch.h: the same results wherever a batch runs), for Reduce. A round of a few rays
  // per shooter costs the farm a round trip per batch; here it costs the rays.
  scheduler::CompletedRound RunLocally(RoundPlan plan);
  // Loop thread: the round is complete; hands its results over. phase() becomes kReducing.
  Result<scheduler::CompletedRound> TakeRound();

  // Loop thread: takes the accepted result of `batch` out of the scheduler to be folded in; true
  // when enough are queued to be worth sending to the worker (TakeFolds). A copy goes to `keep`,
  // for the store (so a restarted master need not lease the batch again).
  bool QueueFold(scheduler::BatchId batch, std::vector<store::StoredBatchResult>* keep);
  // Loop thread: the SHA-256 of the bits of the accepted result QueueFold would take
  // (batch_verifier.h); nullopt when there is none.
  std::optional<ResultDigest> DigestOfResult(scheduler::BatchId batch) const;
  // Loop thread: the round started last (StartPlannedRound).
  uint32_t running_round() const { return running_round_; }
  // Worker thread, before the round's Reduce: the digests of `batches` computed here, as an agent
  // computes them (exact validation, batch_verifier.h). The ray caster is built on first use;
  // Reduce releases it on a large scene (docs/MEMORY.md).
  std::vector<ResultDigest> VerifyBatches(const std::vector<Batch>& batches);
  // Loop thread: the queued results, for Fold.
  std::vector<std::pair<uint32_t, BatchResult>> TakeFolds();
  // Worker thread, after StartPlannedRound and before Reduce, in order: folds in results of the
  // round's batches (index into the plan, result).
  void Fold(std::vector<std::pair<uint32_t, BatchResult>> results);

  // Worker thread, while kReducing: folds the round in and plans the next one.
  // `checkpoint_due`: copy the state for a checkpoint even if the job goes on.
  // `sizing` cuts the next round's batches (the scheduler's suggestion, read on the loop thread
  // before: the scheduler is not thread-safe).
  RoundOutcome Reduce(const scheduler::CompletedRound& round, double round_seconds,
                      bool checkpoint_due, BatchSizing sizing);
  // Loop thread: takes Reduce's outcome back (and installs a refined scene). Returns true when the
  // job goes on (a round is planned), false when it is finished.
  bool InstallOutcome(RoundOutcome& outcome);

  // Recent throughput: rays/s over the last rounds (0 before the first), for pacing.
  double RaysPerSecond() const;
  // Loop thread, for status: the rays of the running round whose batches are in (0 outside
  // kRound); the job's rays with them, so the rays shown count on through a long round such as the
  // final gather and never fall when it ends (a leased round counts whole while it is reduced,
  // Reduce updating totals() meanwhile); and the throughput over the last rounds and the running
  // round so far.
  uint64_t RunningRaysDone(scheduler::TimePoint now) const;
  uint64_t RaysShown(scheduler::TimePoint now) const;
  double RaysPerSecond(scheduler::TimePoint now) const;
  // Loop thread: the share of the job's rays done, the running round's accepted batches included,
  // and the seconds left (core/progress_estimator.h). While kReducing, the figures from before.
  ProgressEstimate Progress(scheduler::TimePoint now) const;
  std::optional<double> EtaSeconds(scheduler::TimePoint now) const {
    return Progress(now).seconds_left;
  }
  scheduler::TimePoint round_started() const { return round_started_; }

 private:
  RunningJob() = default;
  // Worker thread (Prepare, Reduce): the batch sizes the kept results of `round` were planned
  // with, or `fallback` when none are kept.
  BatchSizing SizingFor(uint32_t round, BatchSizing fallback) const;
  // Worker thread: the driver's next plan, its batches cut by `sizing` (nullopt: the job stops).
  std::optional<RoundPlan> PlanNext(BatchSizing sizing);
  // Worker thread: moves the kept results that answer `plan`'s batches exactly to restored_, for
  // StartPlannedRound, and forgets the kept results of its round and those before.
  void RestoreResults(const RoundPlan& plan, BatchSizing sizing);
  // Worker thread: the gather ahead's plan (GatherAhead::Plan with `sizing`) when the job may
  // lease it early, and the sizing the gather round must then be planned with.
  void PlanGatherAhead(BatchSizing sizing, const scheduler::SchedulerOptions& options);
  // Worker thread: encodes the driver's refined scene after a step that split.
  void EncodeRefinedScene();
  // The totals and progress figures of the driver's state, for status.
  void UpdateTotals();
  // The rules for the driver's scene (rules_).
  void UpdateRules();

  store::JobRecord record_;
  SolverSettings settings_;
  // Worker side (Prepare, Reduce, RunLocally): the one round loop, a pool of one thread for its
  // refinement steps and local rounds (it runs inline), and the refined scene's blob and hash
  // (null while the mesh is the bundle's).
  std::unique_ptr<ThreadPool> pool_;
  std::unique_ptr<RoundDriver> driver_;
  std::shared_ptr<const std::vector<uint8_t>> refined_blob_;
  std::shared_ptr<const protocol::PackedScene> refined_packed_;  // refined_blob_ compressed
  // The planned round as the worker folds it in: a copy of the plan it made (the scheduler owns
  // the loop's), and the reduction, begun with the first Fold or in Reduce.
  std::shared_ptr<const RoundPlan> fold_plan_;
  std::unique_ptr<RoundReduction> fold_;
  std::string refined_hash_;      // hex, the store's key
  bool refined_unsaved_ = false;  // no checkpoint has stored refined_blob_ yet
  // Loop side: what agents are sent and fetch. Only the compressed scene: the uncompressed blob
  // is dropped once packed (about 220 bytes a patch, four times the compressed size).
  std::shared_ptr<const protocol::PackedScene> scene_;
  protocol::JobWireInfo wire_;
  scheduler::RoundScheduler scheduler_;
  std::optional<RoundPlan> planned_;
  std::vector<std::pair<uint32_t, BatchResult>> unfolded_;  // accepted, not yet sent to Fold
  // Worker side: results a previous master kept of rounds not planned yet (with
  // checkpoint_seconds above 0, several rounds after the checkpoint), replayed round by round.
  std::vector<store::StoredBatchResult> stored_;
  // Kept results matching the planned round's batches (Prepare, Reduce), for StartPlannedRound.
  std::vector<std::pair<uint32_t, BatchResult>> restored_;
  size_t restored_count_ = 0;
  size_t restore_mismatches_ = 0;
  // The batch sizes the planned round and the running one were planned with (stored with results).
  BatchSizing planned_sizing_;
  BatchSizing running_sizing_;
  uint32_t running_round_ = 0;
  // The gather ahead: planned on the worker (Prepare), leased from the loop thread until the
  // gather round starts; the sizing is the worker's (Reduce plans the gather round with it).
  std::optional<RoundPlan> ahead_plan_;
  std::optional<BatchSizing> ahead_sizing_;
  bool ahead_planned_ = false;  // PlanGatherAhead ran (it runs once a job)
  std::unique_ptr<GatherAhead> ahead_;
  scheduler::SchedulerOptions options_;
  std::vector<std::pair<uint32_t, std::string>> adopted_;
  std::optional<std::string> stop_reason_;
  JobRules rules_;  // written on the worker (Prepare, Reduce), read on the loop outside kReducing
  JobTotals totals_;
  Phase phase_ = Phase::kRound;
  bool meshed_at_submission_ = false;
  scheduler::TimePoint round_started_{};
  // (rays, seconds) of the last rounds, for RaysPerSecond.
  std::vector<std::pair<uint64_t, double>> recent_;
  // A time budget's pace before a round has been timed: the agents' reported speed at the start
  // times kReportedPaceShare (Prepare); 0: unknown, the round is not paced.
  double reported_pace_ = 0;
  // Fed by Reduce (worker), read on the loop thread outside kReducing.
  ProgressEstimator estimator_{0.001};
  // Loop side: the round the scheduler or this machine runs (rays, final gather), and the last
  // estimate, shown while the worker reduces.
  uint64_t running_rays_ = 0;
  uint64_t rays_before_round_ = 0;  // totals_.rays when the running round started
  bool running_gather_ = false;
  JobTimeline timeline_;  // Prepare's (worker, before the loop has the job), then the loop's
  LapClock round_clock_;  // the master's, since Prepare ended or the last round's end
  mutable ProgressEstimate last_progress_;
};

}  // namespace radfarm::daemon
