// The job store's named transactions: the reads and writes of several JobStore calls that the
// master makes as one step on its store thread, as functions a test calls on a temporary store.
//
// Threads: like JobStore itself, call them on the thread that owns the store (the master's store
// thread, daemon/README.md); the results own their data and go back to the loop thread.
// Atomicity: each JobStore write is one SQLite transaction (job_store.h); a function here that
// writes more than once says what an error halfway leaves behind.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "base/result.h"
#include "store/job_state.h"
#include "store/job_store.h"
#include "store/round_totals.h"

namespace radfarm::store {

// What a job needs to start or resume: its record, bundle, latest checkpoint (if any) with the
// refined scene it names, and its rounds (for the totals up to the checkpoint).
struct JobStart {
  JobRecord record;  // read after the job was marked running (started_at_ms is set)
  std::vector<uint8_t> bundle;
  std::optional<Checkpoint> checkpoint;
  // The scene blob checkpoint->scene_hash names; nullopt when there is none or it is missing (the
  // caller fails the job then: a resumed refined job cannot go on without its mesh).
  std::optional<std::vector<uint8_t>> checkpoint_scene;
  std::vector<RoundRecord> rounds;
  // Accepted batch results of the rounds after the checkpoint (JobStore::LoadRoundResults): the
  // round the job resumes with leases only the batches not among them.
  std::vector<StoredBatchResult> round_results;
  // Damaged checkpoints passed over (and deleted) on the way to `checkpoint` and damaged stored
  // round results (deleted), one line each, also appended to the job's events.
  std::vector<std::string> warnings;
};

// Marks up to `slots` queued jobs running, in NextRunnableJobs' order (priority, then age), and
// reads what each needs to start. Errors: a job's bundle missing ("job N: its scene is missing"),
// any store error. An error after the first job leaves the jobs before it marked running; the
// master treats them as it treats running jobs after a crash (RequeueRunningJobs on restart).
Result<std::vector<JobStart>> StartQueuedJobs(JobStore& store, int slots);

// Puts every running job back in the queue with an event saying it resumes (the master's start:
// the previous master stopped while they ran). Returns how many.
Result<int> RequeueRunningJobs(JobStore& store);

// The result of an operator's command.
struct StateChange {
  // The job after the change, or as it was when refused; nullopt: there is no such job.
  std::optional<JobRecord> job;
  // Set when the command is not allowed in the job's state: "job 3 is done: it cannot be paused".
  std::string refused;
};

// Applies `command` (job_state.h: cancel, pause, resume) to job `id` by the transition rules,
// with an event ("cancelled", "paused", "resumed"); a cancel records "cancelled by the operator"
// as the job's error text. A missing job or a refused command is not an error (StateChange says
// which); store errors are.
Result<StateChange> ChangeJobState(JobStore& store, JobId id, JobCommand command);

// Marks job `id` failed with `error`, unless it is already in a terminal state (cancelled while
// its round was reduced, say) or gone: returns whether it changed.
Result<bool> FailJob(JobStore& store, JobId id, const std::string& error);

// A job's latest checkpoint and what turning it into a solution needs.
struct StoredSolution {
  JobRecord job;
  Checkpoint checkpoint;        // the latest
  std::vector<uint8_t> bundle;  // the job's bundle (job.spec.scene_hash)
  // The refined mesh's scene blob the checkpoint's values belong to (checkpoint.scene_hash), or
  // nullopt when they belong to the bundle's mesh.
  std::optional<std::vector<uint8_t>> refined_scene;
  RoundTotals totals;  // the rounds up to the checkpoint's
  // The display drawn from this checkpoint (a finished job's), or empty: none was stored, it was
  // drawn from another round, or it is damaged (whoever needs it draws it again, the same bits).
  std::vector<uint8_t> display;
};

// Loads job `id`'s latest checkpoint with its bundle, refined scene and totals; nullopt when the
// job has no checkpoint yet. Errors: no job `id` ("no job N"), its bundle or its refined scene
// missing ("job N: scene missing", "job N: refined scene H missing"), any store error.
Result<std::optional<StoredSolution>> LoadSolution(JobStore& store, JobId id);

// Holds a running job after a store fault: `held`, with `why` as its reason, and an event
// ("held: " + why). A failed job would be final; a held one resumes from its checkpoints, which
// are intact.
Status HoldJob(JobStore& store, JobId id, const std::string& why);

// Puts held jobs back in the queue: every `held` job, and the jobs of `unrecorded` still marked
// running (their hold could not be written: the store was failing). Returns the ids queued; an
// error when the store still cannot write (they stay held).
Result<std::vector<JobId>> ReleaseHeldJobs(JobStore& store, const std::vector<JobId>& unrecorded);

}  // namespace radfarm::store
