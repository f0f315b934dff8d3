// JobRounds: the master's running jobs. It starts queued jobs (up to max_running_jobs, by
// priority, then age), prepares each on the compute thread, runs its rounds (leased to agents
// through its RunningJob's RoundScheduler, or computed here when small: local_round_rays), reduces
// each round on the compute thread and commits the round and its checkpoint on the store thread
// while the next round already runs; then it finishes or fails the job.
//
// Job lifecycle here (store/job_state.h has the store's side):
//   queued --StartQueuedJobs--> starting --OnJobPrepared--> rounds: BeginRound --OnRoundComplete
//     (or RunRoundHere)--> reducing --OnRoundReduced--> BeginRound ... --> FinishJob --> display
//     --> done; or FailJob
//   DropJob (cancel, pause) forgets a running job at any point; a job still starting is dropped
//   when its preparation ends.
//   A store fault (disk full, I/O error) while a round is committed holds the job instead of
//   failing it (HoldJob, job_holds.cc): `held` with the error as its reason, and RetryHeldJobs puts
//   it back in the queue every hold_retry_ms until the store writes again.
//
// It knows nothing of connections: what it needs of the agents comes through AgentHooks.
// Loop thread only (the compute and store threads hand their results back to it).
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "base/latency_histogram.h"
#include "daemon/config/master_config.h"
#include "daemon/jobs/batch_totals.h"
#include "daemon/jobs/batch_verifier.h"
#include "daemon/jobs/clock.h"
#include "daemon/jobs/display_run.h"
#include "daemon/jobs/result_journal.h"
#include "daemon/jobs/running_job.h"
#include "daemon/jobs/start_handoff.h"
#include "daemon/jobs/start_run.h"
#include "daemon/jobs/store_thread.h"
#include "daemon/scheduler/round_scheduler.h"
#include "loop/async.h"
#include "loop/event_loop.h"
#include "loop/work_queue.h"
#include "store/checkpoint_pacer.h"
#include "store/job_store.h"
#include "store/job_transactions.h"

namespace radfarm::daemon {

// What JobRounds asks of the agent side.
struct AgentHooks {
  std::function<void()> dispatch_all;            // hand leases to every agent with room
  std::function<void(store::JobId)> cancel_job;  // tell every agent to drop the job's batches
  std::function<std::vector<uint64_t>()> available_agents;  // authenticated and not stale
  // Their last reported rays/s, summed (0: none measured yet).
  std::function<double()> reported_rays_per_second;
  // A result of `agent` failed exact validation (`why` names the batch and both digests):
  // blocklist it for the job and close its connections.
  std::function<void(store::JobId, const std::string& agent, const std::string& why)> convict;
  // Available agents that trace the display's points (protocol version 6); none: traced here.
  std::function<size_t()> display_agents;
  // Available agents that trace a direct-light start's patches (version 7); none: traced here.
  std::function<size_t()> start_agents;
  // Available agents that read a scene's sky (version 8): a sky job's start and display points go
  // to them alone; none (or no hook): traced here.
  std::function<size_t()> sky_agents;
};

// Exact validation since the master started (job_verification.cc).
struct VerifyCounters {
  uint64_t verified = 0;    // batches computed again here and compared
  uint64_t mismatched = 0;  // of verified: the agent's bits differed
  uint64_t rewinds = 0;     // jobs sent back before a liar's first result
};

// What the last checkpoint the master committed for a job cost.
struct CheckpointReport {
  uint32_t round = 0;      // the round it ends, as shown (ShownRound: from 1)
  uint64_t bytes = 0;      // its blobs and checksums (store::CheckpointCost)
  double copy_ms = 0;      // copying the state from the solver, on the compute thread
  double encode_ms = 0;    // encoding it, on the store thread
  double commit_ms = 0;    // committing it
  double queued_ms = 0;    // from queueing on the store thread to the commit, waiting included
  uint64_t committed = 0;  // checkpoints this master committed for the job
};

class JobRounds {
 public:
  using Runners = std::map<store::JobId, std::shared_ptr<RunningJob>>;

  JobRounds(loop::EventLoop& loop, const Clock& clock, const MasterConfig& config,
            const scheduler::SchedulerOptions& options, StoreThread& store,
            loop::WorkQueue& compute, AgentHooks agents);
  ~JobRounds();
  JobRounds(const JobRounds&) = delete;
  JobRounds& operator=(const JobRounds&) = delete;

  // Starts queued jobs while there are free slots (after a submit, a resume, a job's end).
  void StartQueuedJobs();
  // The scene of job `id`, just submitted, as the submission's check meshed it: if the next
  // StartQueuedJobs starts the job, its preparation takes this mesh instead of meshing again (at
  // 10^5-10^6 patches, seconds). Otherwise it is dropped then, so a queued job holds no mesh.
  // One at a time: a newer one replaces it.
  void OfferSubmittedMesh(store::JobId id, SubmittedMesh mesh);
  // A batch result of the job's round, computed by the agent called `agent`, was accepted: it
  // goes on to be folded in, and is perhaps verified (batch_verifier.h).
  void OnResultAccepted(store::JobId id, scheduler::BatchId batch, const std::string& agent);
  // The last batch of the job's round is in: reduce it.
  void OnRoundComplete(store::JobId id);
  // Forgets a job the operator cancelled or paused (the store knows already).
  void DropJob(store::JobId id);
  void FailJob(store::JobId id, const std::string& error);
  // An error of a store fault's kind (store::IsStoreFault): hold the job (store/job_state.h); any
  // other error fails it.
  void HoldOrFail(store::JobId id, const Error& error);
  // After round `round`'s checkpoint committed: its kept results and those before go, in a store
  // transaction of their own (store/job_store.h PruneRoundResults). UINT32_MAX: all of them, for
  // a job that ended.
  void PruneKeptResults(store::JobId id, uint32_t round);
  // From a timer: at most every hold_retry_ms, held jobs go back to the queue if the store writes.
  void RetryHeldJobs(uint64_t now_ms);

  // The running jobs (not those being prepared), by id.
  const Runners& runners() const { return runners_; }
  RunningJob* FindRunner(uint64_t job_id);
  // The jobs in a round, and those between rounds with a gather ahead (gather_ahead.h), highest
  // priority first; equal priorities take turns being first.
  std::vector<RunningJob*> RunnersByPriority();
  size_t starting() const { return starting_.size(); }
  // The batch counters of every job since the master started: the finished runners' and the
  // running ones' (for /metrics).
  BatchTotals batch_totals(scheduler::TimePoint now) const;
  // What the store kept of the rounds in progress, and what restarts found there.
  const JournalCounters& journal() const { return journal_.counters(); }
  const VerifyCounters& verification() const { return verify_counters_; }
  uint64_t batches_restored() const { return batches_restored_; }
  // Results of final gathers computed ahead of their rounds and accepted there (gather_ahead.h).
  uint64_t gather_ahead_adopted() const { return gather_ahead_adopted_; }
  // Seconds from queueing each checkpoint on the store thread to its commit.
  const LatencyHistogram& checkpoint_latency() const { return checkpoint_latency_; }
  // The last checkpoint this master committed for job `id`, or null: kept for the
  // kKeptCheckpointReports most recent jobs, finished ones included (the control socket's
  // last_checkpoint).
  const CheckpointReport* LastCheckpoint(store::JobId id) const;
  // What the rules gave job `id`'s scene (RunningJob::rules), or null: kept as LastCheckpoint is,
  // so a job drawing its display, or done, still shows them.
  const JobRules* RulesOf(store::JobId id) const;
  // Where job `id`'s time went on this master (core/job_timeline.h): a running job's so far, one
  // drawing its display, or a finished one's (kept as LastCheckpoint is); null for any other, and
  // what ran before a restart of the master is not in it.
  const JobTimeline* TimelineOf(store::JobId id) const;
  // "preparing" (being meshed and loaded), "round", "reducing", "finishing" or "display" (its
  // display being drawn, job_display.cc) for a job this master runs; empty for any other.
  std::string_view PhaseOf(store::JobId id) const;
  // The seconds job `id`'s display has left (DisplaySecondsLeft), or nullopt: not drawing its
  // display, or no estimate yet.
  std::optional<double> DisplaySecondsLeft(store::JobId id) const;
  // The round and rays job `id`'s finished solve showed, while its display is drawn; nullopt for
  // any other job.
  std::optional<SolveShown> DisplayedSolve(store::JobId id) const;
  // --- Point work on the agents: starts and displays (job_point_leases.cc) ---
  // New pieces of the starts (to agents of protocol version 7) and displays (version 6) under way
  // for `agent`, while it holds fewer than `room` of each; none of a job `refused(job)` says the
  // agent may not work for (blocklisted).
  std::vector<protocol::PointLeaseMsg> PointLeasesFor(
      uint64_t agent, uint16_t version, uint32_t room,
      const std::function<bool(store::JobId)>& refused);
  // A PointResult of `agent`: true when it is its piece's first (accepted), false when dropped
  // (late, of an earlier step or a job no longer drawn). An error (values that do not answer the
  // piece's work) names what is wrong; the agent's pieces are then queued again, and the caller
  // treats it as a liar.
  Result<bool> OnPointResult(uint64_t agent, const protocol::PointResultMsg& result);
  // The agent went: its pieces go back to the queue.
  void OnPointAgentLost(uint64_t agent);
  // The agent gave a piece back (LeaseReturn); returns 1 when it held it, else 0.
  size_t ReturnPointPieces(uint64_t agent, const protocol::LeaseRef& lease);
  // The point context of a display's step under lease, for the agents' SceneRequests; null
  // when no display under way has this hash.
  std::shared_ptr<const protocol::PackedScene> PointContextOf(
      const protocol::SceneHash& hash) const;
  // Some display's step is leased: idle agents should be offered its pieces on every tick.
  bool LeasingPoints() const;

  // Offers overdue leases again (RoundScheduler::Tick); returns how many.
  size_t Tick(scheduler::TimePoint now);
  // Whether some job's round is in its end game (RoundScheduler::InEndGame): idle agents should be
  // offered work on every tick, not only when they speak.
  bool InEndGame() const;

  // Shutdown: no new work starts, results coming back are dropped, a start the compute thread
  // waits for ends with an error.
  void Stop();
  // After the store thread drained: the runners go.
  void Clear() { runners_.clear(); }

 private:
  // --- Direct-light starts (job_start.cc) ---
  // What traces job `id`'s starts: the agents, through start_handoff_.
  StartLightSource StartSourceFor(store::JobId id) const;
  // The starts the compute thread handed over: leased, or sent back to be traced there.
  void TakeStartRequests();
  // A PointResult of a piece of `run` (OnPointResult's contract).
  Result<bool> OnStartResult(uint64_t agent, StartRun& run, const protocol::PointResultMsg& result);
  // Ends job `id`'s start under lease, if any: the compute thread's wait ends with an error.
  void DropStart(store::JobId id);
  // With no agent left that takes start work, the starts under lease are traced on the compute
  // thread instead (Tick): a job does not wait for agents that may never come back.
  void TakeBackOrphanedStarts();
  // The available agents that may trace a start: of version 8 for a scene with a sky, else 7.
  size_t StartAgents(bool sky) const;
  // Adds the agents' seconds on the runner's last start to its timeline.
  void AddStartSeconds(RunningJob& runner);

  void OnJobPrepared(store::JobId id, Result<std::shared_ptr<RunningJob>> runner);
  // Leases the job's final gather ahead (gather_ahead.h) if its preparation or last reduction
  // planned one and the agents, not this master, will compute the gather. False when it failed
  // the job.
  bool StartGatherAhead(const std::shared_ptr<RunningJob>& runner);
  // Starts the planned round on the agents, or computes it here when it is small
  // (MasterConfig::local_round_rays).
  void BeginRound(const std::shared_ptr<RunningJob>& runner);
  // Exact validation (job_verification.cc). The round just started gets a fresh verifier round.
  void StartVerifying(const std::shared_ptr<RunningJob>& runner);
  // Computes the digests of the round's batches `indices` on the compute thread and compares them.
  void VerifyOnComputeThread(const std::shared_ptr<RunningJob>& runner,
                             std::vector<uint32_t> indices);
  void OnBatchesVerified(const std::shared_ptr<RunningJob>& runner, uint32_t round,
                         const std::vector<uint32_t>& indices,
                         const std::vector<ResultDigest>& digests);
  // The round is complete: true when every verification of it agreed; otherwise the end-of-round
  // picks are sent to be verified and OnRoundComplete runs again after the last one (the barrier).
  bool RoundVerified(const std::shared_ptr<RunningJob>& runner);
  // A result failed verification: the agent is convicted, the runner dropped, and the job goes
  // back in the store to before the agent's first result (RewindJob) and is queued again.
  void Rewind(const std::shared_ptr<RunningJob>& runner, const Mismatch& mismatch);
  void RunRoundHere(const std::shared_ptr<RunningJob>& runner);
  // Sends the runner's queued results (TakeFolds) to the compute thread to be folded in.
  void SendFolds(const std::shared_ptr<RunningJob>& runner);
  // `work` (Reduce, perhaps after RunLocally) on the compute thread, then OnRoundReduced.
  void ReduceOnComputeThread(const std::shared_ptr<RunningJob>& runner,
                             std::function<RoundOutcome()> work);
  void OnRoundReduced(const std::shared_ptr<RunningJob>& runner, RoundOutcome outcome);
  // The job's rounds are over: its display is drawn from its last checkpoint and stored with it
  // (job_display.cc), then the job is done.
  void FinishJob(const std::shared_ptr<RunningJob>& runner);
  // The display run of job `id` started as `serial`, or null (dropped, or a later run's).
  DisplayRun* FindDisplay(store::JobId id, uint64_t serial);
  // `direct_light`: the solve's start, when the runner had it (else empty: computed again).
  void PlanDisplay(store::JobId id, uint64_t serial, store::StoredSolution solution,
                   std::vector<Rgb> direct_light);
  // Leases the draft's next step, traces it here, or finishes the display.
  void NextDisplayStep(store::JobId id, uint64_t serial);
  // The step's values (traced here when nullopt) go to the draft on the compute thread.
  void ApplyDisplayStep(store::JobId id, uint64_t serial, std::optional<PointValues> values);
  void FinishDisplay(store::JobId id, uint64_t serial);
  // The display could not be drawn: the job fails, saying why.
  void DisplayFailed(store::JobId id, const std::string& error);
  void MarkDone(store::JobId id, uint64_t serial, std::optional<store::StoredDisplay> display);
  // Keeps `report` as job `id`'s last checkpoint, its count one more; forgets the oldest job's
  // beyond kKeptCheckpointReports.
  void RecordCheckpoint(store::JobId id, CheckpointReport report);
  // Keeps `rules` as job `id`'s (an event when they change); forgets the oldest job's beyond
  // kKeptCheckpointReports.
  void KeepRules(store::JobId id, const JobRules& rules);
  // Stops a job's work on every agent (Cancel) and forgets its runner.
  void DropRunner(store::JobId id);

  const Clock& clock_;
  const MasterConfig& config_;
  const scheduler::SchedulerOptions& options_;
  StoreThread& store_;
  loop::WorkQueue& compute_;
  AgentHooks agents_;

  Runners runners_;
  // Starts handed from the compute thread (start_handoff.h), woken by start_wake_.
  std::shared_ptr<StartHandoff> start_handoff_;
  std::unique_ptr<loop::Async> start_wake_;
  std::map<store::JobId, StartRun> start_runs_;
  uint32_t start_serial_ = 0;
  std::map<store::JobId, double> start_agent_seconds_;  // until the runner is back on the loop
  // Finished jobs whose display is being drawn and stored.
  std::map<store::JobId, DisplayRun> display_runs_;
  uint64_t display_serial_ = 0;
  ResultJournal journal_;
  uint64_t verify_seed_;                             // secret: agents cannot predict samples
  std::map<store::JobId, BatchVerifier> verifiers_;  // of the running jobs
  std::set<store::JobId> awaiting_verification_;     // complete rounds held at the barrier
  VerifyCounters verify_counters_;
  uint64_t batches_restored_ = 0;
  uint64_t gather_ahead_adopted_ = 0;
  BatchTotals retired_;  // the counters of runners that went
  LatencyHistogram checkpoint_latency_;
  static constexpr size_t kKeptCheckpointReports = 256;
  std::map<store::JobId, CheckpointReport> checkpoint_reports_;  // by id: oldest job first
  std::map<store::JobId, JobRules> job_rules_;                   // likewise
  std::map<store::JobId, JobTimeline> timelines_;                // of finished jobs, likewise
  store::CheckpointPacer checkpoints_;                           // which rounds write a checkpoint
  std::map<store::JobId, bool> starting_;  // being prepared; true once cancelled meanwhile
  // OfferSubmittedMesh's, until the next start pass takes or drops it.
  store::JobId submitted_mesh_job_ = 0;
  SubmittedMesh submitted_mesh_;
  bool start_pending_ = false;  // a StartQueuedJobs query is in flight
  bool start_again_ = false;    // ... and another was asked for meanwhile
  size_t dispatch_rotation_ = 0;
  bool stopping_ = false;
  // Held jobs: some were held (perhaps by an earlier master) and wait for RetryHeldJobs; those
  // whose hold could not be written are still "running" in the store.
  bool holds_waiting_ = true;  // a master starts by looking for holds left from before
  std::vector<store::JobId> unrecorded_holds_;
  uint64_t next_hold_retry_ms_ = 0;
  bool hold_retry_pending_ = false;
};

}  // namespace radfarm::daemon
