// JobStore: the master daemon's durable state in one SQLite file: jobs and their states, scenes by
// hash, one row per solver round, solver checkpoints, agents seen and an event log.
//
// Design. The file is opened in WAL mode with synchronous=FULL (a committed transaction survives
// power loss: the daemon replies to a client or agent only after the commit returns), foreign keys
// on and a busy timeout. Open() checks the file (ours, not corrupt, not newer; see schema.h) before
// writing anything, then migrates it to the latest schema. Every write that touches more than one
// row runs in one IMMEDIATE transaction, so a failure (SQLITE_FULL, SQLITE_IOERR, a constraint)
// leaves nothing partial behind.
//
// Threads and ownership. A JobStore is NOT thread-safe. The daemon creates it and moves it to one
// dedicated store thread (a single-thread loop::WorkQueue), which owns it for its whole life;
// the loop thread never calls it. Results go back to the loop as the WorkQueue's `done` values:
// copy what you need out of the returned structs, which own their data.
//
// Errors. Expected failures are Status/Result errors whose message names the file, the operation,
// the SQLite code (SQLITE_BUSY, SQLITE_CORRUPT, SQLITE_NOTADB, SQLITE_FULL, SQLITE_IOERR, ...) and
// what to do. "Not found" is not an error: lookups return std::optional.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "base/result.h"
#include "core/batch.h"
#include "core/progressive_solver.h"
#include "core/rgb.h"
#include "store/database.h"
#include "store/job_state.h"
#include "store/schema.h"

namespace radfarm::store {

using JobId = int64_t;

struct JobStoreOptions {
  DatabaseOptions database;
  SchemaCheckOptions check;
  // Milliseconds since the Unix epoch; tests inject a fake clock. Default: the system clock.
  std::function<int64_t()> now_ms;
  // PRAGMA max_page_count for this connection (0: SQLite's default, no practical limit). A cap for
  // operators, and how tests simulate a full disk.
  int64_t max_pages = 0;
};

struct JobSpec {
  std::string name;
  std::string scene_hash;  // must already be stored (PutScene)
  std::string settings;    // the job's solver settings, serialized by the caller; opaque here
  uint64_t seed = 1;
  int64_t priority = 0;  // higher runs first
};

struct JobRecord {
  JobId id = 0;
  JobSpec spec;
  JobState state = JobState::kQueued;
  int64_t submitted_at_ms = 0;
  std::optional<int64_t> started_at_ms;
  std::optional<int64_t> finished_at_ms;
  std::optional<std::string> error;
};

struct RoundRecord {
  JobId job = 0;
  uint32_t round = 0;
  uint32_t shooters = 0;
  uint64_t rays = 0;
  double unshot_fraction = 0;
  double unshot_power = 0;
  double duration_seconds = 0;
  uint64_t escaped_rays = 0;  // rays of the round that left the scene (schema version 3)
  uint64_t back_rays = 0;     // rays of the round that hit a patch's back
};

struct Checkpoint {
  JobId job = 0;
  uint32_t round = 0;        // the round whose results it includes
  uint32_t rounds_done = 0;  // ProgressiveSolver::rounds_done() at that point
  std::vector<Rgb> radiosity;
  std::vector<Rgb> unshot;  // same size as radiosity
  EnergyAccount energy;
  int64_t created_at_ms = 0;  // set by the store
  // Adaptive refinement (schema version 4): the hash of the refined mesh's scene blob the values
  // belong to, which must be stored (PutScene) first; nullopt: the mesh the job's bundle makes.
  std::optional<std::string> scene_hash;
  uint32_t refine_points = 0;  // refinement points passed (mesh/refinement_schedule.h)
  // Set on the checkpoint of the round the solve stopped after (schema version 4): why it stopped
  // (core/solve_control.h). A resume from it runs no further round.
  std::optional<std::string> stop_reason;
};

// What one SaveCheckpoint cost, for the master's log and the benchmarks.
struct CheckpointCost {
  uint64_t bytes = 0;         // the row's blobs and checksum
  double encode_seconds = 0;  // encoding and checksumming, before the transaction
  double commit_seconds = 0;  // the transaction, its commit (fsync) and WAL checkpointing
};

// A checkpoint whose bytes no longer match their checksum (rot on disk: blob_checksum.h).
struct DamagedCheckpoint {
  uint32_t round = 0;
  std::string message;  // "job store PATH: the checkpoint of job 3 round 7 is damaged (...)"
};

// One accepted batch result of a round in progress (schema version 6), kept until the round's
// checkpoint, so a restarted master leases again only the batches it had not received.
struct StoredBatchResult {
  uint32_t index = 0;       // into the round's plan.batches
  uint32_t batch_rays = 0;  // the batch size the round was planned with
  uint32_t taper_ways = 0;  // and its taper (core/batch.h BatchSizing): the column's high bits
  Batch batch;              // plan.batches[index] (its round is the result's round)
  BatchResult result;
};

// Stored round results of a job, verified against their checksums.
struct StoredRoundResults {
  std::vector<StoredBatchResult> results;  // by round, then index
  // One line per damaged row found (and deleted): its batch is leased again.
  std::vector<std::string> damaged;
};

// A finished job's display (codec/display_blob.h's bytes) and the checkpoint round it was drawn
// from.
struct StoredDisplay {
  uint32_t round = 0;
  std::vector<uint8_t> display;
};

enum class EventLevel { kInfo, kWarning, kError };

struct Event {
  int64_t id = 0;
  std::optional<JobId> job;  // nullopt: a farm-wide event
  int64_t time_ms = 0;
  EventLevel level = EventLevel::kInfo;
  std::string text;
};

struct AgentRecord {
  std::string name;
  std::string address;
  uint32_t threads = 0;
  int64_t first_seen_ms = 0;
  int64_t last_seen_ms = 0;
};

// An enrolled agent (agent_credentials): its key is protocol::DeriveAgentKey(secret, name,
// generation); a revoked one is refused at the handshake.
struct AgentCredential {
  std::string name;
  uint64_t generation = 0;
  bool revoked = false;
  int64_t enrolled_at_ms = 0;
  std::optional<int64_t> revoked_at_ms;
};

class JobStore {
 public:
  // Opens or creates the store at `path` (checks, then migrates; see the design note).
  static Result<JobStore> Open(const std::string& path, JobStoreOptions options = {});

  JobStore(JobStore&&) noexcept = default;
  JobStore& operator=(JobStore&&) noexcept = default;
  JobStore(const JobStore&) = delete;
  JobStore& operator=(const JobStore&) = delete;

  // --- jobs (lifecycle in job_state.h) ---
  Result<JobId> SubmitJob(const JobSpec& spec);
  Result<std::vector<JobRecord>> ListJobs();  // by id
  Result<std::optional<JobRecord>> GetJob(JobId id);
  // Refuses transitions not in the diagram, an error text on any state but kFailed/kCancelled, and
  // kFailed without one. Atomic: the state read and the update are one transaction.
  Status SetJobState(JobId id, JobState to, std::optional<std::string> error = std::nullopt);
  // Queued jobs, highest priority first, then earliest submission, then lowest id; at most `limit`.
  Result<std::vector<JobRecord>> NextRunnableJobs(int limit);

  // --- scenes ---
  // Idempotent for the same bytes; an error if `hash` is stored with different bytes.
  Status PutScene(const std::string& hash, std::span<const uint8_t> geometry);
  // Verified against its checksum: damaged bytes are an error naming the scene.
  Result<std::optional<std::vector<uint8_t>>> GetScene(const std::string& hash);

  // --- rounds and checkpoints ---
  // Recording a round again (after resuming from an earlier checkpoint) replaces its row.
  Status RecordRound(const RoundRecord& round);
  Result<std::vector<RoundRecord>> ListRounds(JobId job);
  // Writes the round row and the checkpoint of its results in one transaction: both or neither.
  // checkpoint.job and .round must equal round.job and .round; checkpoint.scene_hash, when set,
  // must be stored. The job's stored round results up to that round go in the same transaction.
  // `cost`, when given, is filled in.
  Status SaveCheckpoint(const RoundRecord& round, const Checkpoint& checkpoint,
                        CheckpointCost* cost = nullptr);
  // The checkpoint with the highest round, with the same bits that were saved, verified against
  // its checksum. A damaged one is an error when `damaged` is null; otherwise it is appended
  // there and the next older checkpoint is tried (none left: nullopt, the job starts over).
  Result<std::optional<Checkpoint>> LoadLatestCheckpoint(
      JobId job, std::vector<DamagedCheckpoint>* damaged = nullptr);
  Status DeleteCheckpoint(JobId job, uint32_t round);
  // The stop_reason of the checkpoint with the highest round (none: no checkpoint, or the job
  // had not stopped there), without reading its arrays.
  Result<std::optional<std::string>> LoadLatestStopReason(JobId job);
  // Keeps the `keep_last` checkpoints with the highest rounds and deletes the rest (0 deletes all).
  // Freed pages are reused by later checkpoints, so the file stays near keep_last+1 checkpoints.
  Status PruneCheckpoints(JobId job, int keep_last);
  Result<int64_t> CountCheckpoints(JobId job);
  // The round and created_at_ms of the checkpoint with the highest round, without reading its
  // arrays or checking them (what a preview of it is cached under); nullopt: none.
  Result<std::optional<std::pair<uint32_t, int64_t>>> LatestCheckpointStamp(JobId job);

  // --- results of the round in progress (round_results, see StoredBatchResult) ---
  // Writes `results` (all of job `job`) in one transaction; a result stored again replaces the row.
  Status SaveRoundResults(JobId job, std::span<const StoredBatchResult> results);
  // The job's stored results of rounds after `after_round` (all rounds when nullopt). A row whose
  // bytes do not match its checksum, or do not decode, is deleted and named in `damaged`.
  Result<StoredRoundResults> LoadRoundResults(JobId job, std::optional<uint32_t> after_round);
  Result<int64_t> CountRoundResults(JobId job, uint32_t round);
  // Deletes the kept results of round `up_to_round` and before, which its checkpoint made
  // needless. SaveCheckpoint leaves them (a restart reads only rounds after its checkpoint) so its
  // commit does not wait for their deletion; call this after it, in a transaction of its own.
  Status PruneRoundResults(JobId job, uint32_t up_to_round);
  // Deletes the kept results of every job that is done, failed or cancelled: an ended job is
  // never resumed. The master prunes each job as it ends, after saying so; this takes the rows a
  // master stopped between the two left behind (at its start).
  Status PruneEndedJobsRoundResults();
  // A liar was caught (daemon/jobs/batch_verifier.h): in one transaction, deletes the checkpoints
  // of round `from_round` and later and the kept results of the rounds after it, and of
  // `from_round` itself those of the batches in `discard` (or all of them when `discard_all`).
  // A master that restarts then resumes before the lie, as the running one does.
  Status RewindJob(JobId job, uint32_t from_round, std::span<const uint32_t> discard,
                   bool discard_all);

  // --- displays (a finished job's, drawn from its checkpoint of round `round`) ---
  // Replaces the job's display, if it had one.
  Status PutDisplay(JobId job, uint32_t round, std::span<const uint8_t> display);
  // Verified against its checksum: damaged bytes are an error naming the job.
  Result<std::optional<StoredDisplay>> GetDisplay(JobId job);

  // --- agents and events ---
  Status RecordAgentSeen(const std::string& name, const std::string& address, uint32_t threads);
  Result<std::vector<AgentRecord>> ListAgents();
  // Enrolls `name`: generation 1, or the next one if it was enrolled before (a new key), and
  // not revoked.
  Result<AgentCredential> EnrollAgent(const std::string& name);
  // Marks `name` revoked; nullopt if it was never enrolled.
  Result<std::optional<AgentCredential>> RevokeAgent(const std::string& name);
  Result<std::vector<AgentCredential>> ListAgentCredentials();
  Status AppendEvent(std::optional<JobId> job, EventLevel level, const std::string& text);
  // The last `limit` events of `job` (nullopt: farm-wide ones), oldest first.
  Result<std::vector<Event>> ListEvents(std::optional<JobId> job, int limit);
  // The last `limit` events of the farm and every job together, oldest first (the status page).
  Result<std::vector<Event>> ListRecentEvents(int limit);

  const std::string& path() const { return db_.path(); }

 private:
  JobStore(Database db, std::function<int64_t()> now_ms)
      : db_(std::move(db)), now_ms_(std::move(now_ms)) {}
  Status InsertRound(const RoundRecord& round, int64_t now);

  Database db_;
  std::function<int64_t()> now_ms_;
};

std::string_view EventLevelName(EventLevel level);

}  // namespace radfarm::store
