#include "store/job_transactions.h"

#include <algorithm>
#include <utility>

namespace radfarm::store {
namespace {

std::string JobName(JobId id) { return "job " + std::to_string(id); }

// The job's record after a write, which must still be there.
Result<JobRecord> ReadBack(JobStore& store, JobId id, const char* what) {
  Result<std::optional<JobRecord>> job = store.GetJob(id);
  if (!job || !*job) return Error{JobName(id) + what};
  return std::move(**job);
}

}  // namespace

Result<std::vector<JobStart>> StartQueuedJobs(JobStore& store, int slots) {
  Result<std::vector<JobRecord>> next = store.NextRunnableJobs(slots);
  RADFARM_RETURN_IF_ERROR(next);
  std::vector<JobStart> starts;
  for (JobRecord& record : *next) {
    RADFARM_RETURN_IF_ERROR(store.SetJobState(record.id, JobState::kRunning));
    JobStart start;
    Result<std::optional<std::vector<uint8_t>>> bundle = store.GetScene(record.spec.scene_hash);
    RADFARM_RETURN_IF_ERROR(bundle);
    if (!*bundle) return Error{JobName(record.id) + ": its scene is missing"};
    start.bundle = std::move(**bundle);
    std::vector<DamagedCheckpoint> damaged;
    Result<std::optional<Checkpoint>> checkpoint = store.LoadLatestCheckpoint(record.id, &damaged);
    RADFARM_RETURN_IF_ERROR(checkpoint);
    start.checkpoint = std::move(*checkpoint);
    // Rot in a checkpoint: the job resumes from the one before (or from the start) and computes
    // the same bits again; the damaged rows go, so nothing reads them later.
    for (const DamagedCheckpoint& d : damaged) {
      const std::string warning =
          d.message + "; resuming from " +
          (start.checkpoint ? "round " + std::to_string(start.checkpoint->round)
                            : std::string("the start")) +
          ", the later rounds are computed again";
      (void)store.AppendEvent(record.id, EventLevel::kWarning, warning);
      RADFARM_RETURN_IF_ERROR(store.DeleteCheckpoint(record.id, d.round));
      start.warnings.push_back(warning);
    }
    if (start.checkpoint && start.checkpoint->scene_hash) {
      Result<std::optional<std::vector<uint8_t>>> scene =
          store.GetScene(*start.checkpoint->scene_hash);
      RADFARM_RETURN_IF_ERROR(scene);
      start.checkpoint_scene = std::move(*scene);
    }
    Result<std::vector<RoundRecord>> rounds = store.ListRounds(record.id);
    RADFARM_RETURN_IF_ERROR(rounds);
    start.rounds = std::move(*rounds);
    // A master killed between a checkpoint and the pruning of its round's results left those
    // rows behind: nothing reads them again, so they go now rather than at the next checkpoint.
    if (start.checkpoint) {
      RADFARM_RETURN_IF_ERROR(store.PruneRoundResults(record.id, start.checkpoint->round));
    }
    // Results of the rounds after the checkpoint a previous master had received; damaged ones
    // are dropped (and deleted) and their batches leased again.
    Result<StoredRoundResults> kept = store.LoadRoundResults(
        record.id, start.checkpoint ? std::optional(start.checkpoint->round) : std::nullopt);
    RADFARM_RETURN_IF_ERROR(kept);
    start.round_results = std::move(kept->results);
    for (const std::string& warning : kept->damaged) {
      (void)store.AppendEvent(record.id, EventLevel::kWarning, warning);
      start.warnings.push_back(warning);
    }
    Result<JobRecord> fresh = ReadBack(store, record.id, " vanished");
    RADFARM_RETURN_IF_ERROR(fresh);
    start.record = std::move(*fresh);
    starts.push_back(std::move(start));
  }
  return starts;
}

Result<int> RequeueRunningJobs(JobStore& store) {
  Result<std::vector<JobRecord>> jobs = store.ListJobs();
  RADFARM_RETURN_IF_ERROR(jobs);
  int requeued = 0;
  for (const JobRecord& job : *jobs) {
    if (job.state != JobState::kRunning) continue;
    RADFARM_RETURN_IF_ERROR(store.SetJobState(job.id, JobState::kQueued));
    (void)store.AppendEvent(job.id, EventLevel::kInfo,
                            "master restarted: the job resumes from its latest checkpoint");
    ++requeued;
  }
  return requeued;
}

Result<StateChange> ChangeJobState(JobStore& store, JobId id, JobCommand command) {
  Result<std::optional<JobRecord>> job = store.GetJob(id);
  RADFARM_RETURN_IF_ERROR(job);
  StateChange change;
  if (!*job) return change;
  const JobState from = (*job)->state;
  if (!IsAllowedCommand(from, command)) {
    change.refused = JobName(id) + " is " + std::string(JobStateName(from)) + ": it cannot be " +
                     std::string(JobCommandDone(command));
    change.job = std::move(**job);
    return change;
  }
  const JobState to = CommandTarget(command);
  std::optional<std::string> reason;
  if (to == JobState::kCancelled) reason = "cancelled by the operator";
  RADFARM_RETURN_IF_ERROR(store.SetJobState(id, to, reason));
  (void)store.AppendEvent(id, EventLevel::kInfo, std::string(JobCommandDone(command)));
  Result<JobRecord> after = ReadBack(store, id, " cannot be read back");
  RADFARM_RETURN_IF_ERROR(after);
  change.job = std::move(*after);
  return change;
}

Result<bool> FailJob(JobStore& store, JobId id, const std::string& error) {
  Result<std::optional<JobRecord>> job = store.GetJob(id);
  RADFARM_RETURN_IF_ERROR(job);
  if (!*job || IsTerminal((*job)->state)) return false;
  RADFARM_RETURN_IF_ERROR(store.SetJobState(id, JobState::kFailed, error));
  return true;
}

Result<std::optional<StoredSolution>> LoadSolution(JobStore& store, JobId id) {
  Result<std::optional<JobRecord>> job = store.GetJob(id);
  RADFARM_RETURN_IF_ERROR(job);
  if (!*job) return Error{"no " + JobName(id)};
  // A finished job's solution is its last checkpoint: a damaged one is an error, never an older
  // solution in its place. A job still on its way shows its latest good one.
  std::vector<DamagedCheckpoint> damaged;
  const bool finished = IsTerminal((*job)->state);
  Result<std::optional<Checkpoint>> checkpoint =
      store.LoadLatestCheckpoint(id, finished ? nullptr : &damaged);
  if (!checkpoint) {
    return Error{checkpoint.error() +
                 ": the solution cannot be fetched; restore the store from a backup or submit "
                 "the job again"};
  }
  if (!*checkpoint) return std::optional<StoredSolution>();
  StoredSolution solution;
  solution.job = std::move(**job);
  solution.checkpoint = std::move(**checkpoint);
  Result<std::optional<std::vector<uint8_t>>> bundle = store.GetScene(solution.job.spec.scene_hash);
  if (!bundle || !*bundle) return Error{JobName(id) + ": scene missing"};
  solution.bundle = std::move(**bundle);
  if (const std::optional<std::string>& hash = solution.checkpoint.scene_hash) {
    Result<std::optional<std::vector<uint8_t>>> scene = store.GetScene(*hash);
    if (!scene || !*scene) return Error{JobName(id) + ": refined scene " + *hash + " missing"};
    solution.refined_scene = std::move(**scene);
  }
  Result<std::vector<RoundRecord>> rounds = store.ListRounds(id);
  RADFARM_RETURN_IF_ERROR(rounds);
  solution.totals = TotalsUpToRound(*rounds, solution.checkpoint.round);
  Result<std::optional<StoredDisplay>> display = store.GetDisplay(id);
  if (display && *display && (*display)->round == solution.checkpoint.round) {
    solution.display = std::move((*display)->display);
  }
  return std::optional(std::move(solution));
}

Status HoldJob(JobStore& store, JobId id, const std::string& why) {
  RADFARM_RETURN_IF_ERROR(store.SetJobState(id, JobState::kHeld, why));
  (void)store.AppendEvent(id, EventLevel::kWarning, "held: " + why);
  return Ok{};
}

Result<std::vector<JobId>> ReleaseHeldJobs(JobStore& store, const std::vector<JobId>& unrecorded) {
  Result<std::vector<JobRecord>> jobs = store.ListJobs();
  RADFARM_RETURN_IF_ERROR(jobs);
  std::vector<JobId> released;
  for (const JobRecord& job : *jobs) {
    const bool held = job.state == JobState::kHeld;
    const bool unrecorded_hold =
        job.state == JobState::kRunning &&
        std::find(unrecorded.begin(), unrecorded.end(), job.id) != unrecorded.end();
    if (!held && !unrecorded_hold) continue;
    // A write: while the store still fails, this fails too and the job stays held.
    RADFARM_RETURN_IF_ERROR(store.SetJobState(job.id, JobState::kQueued));
    (void)store.AppendEvent(job.id, EventLevel::kInfo,
                            "released: the store writes again; the job resumes from its latest "
                            "checkpoint");
    released.push_back(job.id);
  }
  return released;
}

}  // namespace radfarm::store
