#include "store/job_store.h"

#include <chrono>
#include <filesystem>
#include <utility>

#include "base/result.h"
#include "store/blob_checksum.h"

namespace radfarm::store {
namespace {

int64_t SystemNowMs() {
  return std::chrono::duration_cast<std::chrono::milliseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

std::optional<int64_t> OptionalInt(const Statement& stmt, int column) {
  if (stmt.IsNull(column)) return std::nullopt;
  return stmt.Int(column);
}

constexpr std::string_view kJobColumns =
    "id, name, scene_hash, settings, seed, priority, state, submitted_at_ms, started_at_ms, "
    "finished_at_ms, error";

Result<JobRecord> ReadJob(const Statement& stmt) {
  JobRecord job;
  job.id = stmt.Int(0);
  job.spec.name = stmt.Text(1);
  job.spec.scene_hash = stmt.Text(2);
  job.spec.settings = stmt.Text(3);
  job.spec.seed = static_cast<uint64_t>(stmt.Int(4));  // stored as the same 64 bits
  job.spec.priority = stmt.Int(5);
  std::string state = stmt.Text(6);
  std::optional<JobState> parsed = ParseJobState(state);
  if (!parsed) return Error{"job " + std::to_string(job.id) + ": unknown state '" + state + "'"};
  job.state = *parsed;
  job.submitted_at_ms = stmt.Int(7);
  job.started_at_ms = OptionalInt(stmt, 8);
  job.finished_at_ms = OptionalInt(stmt, 9);
  if (!stmt.IsNull(10)) job.error = stmt.Text(10);
  return job;
}

Result<std::vector<JobRecord>> ReadJobs(Statement& stmt) {
  std::vector<JobRecord> jobs;
  while (true) {
    Result<bool> row = stmt.Step();
    RADFARM_RETURN_IF_ERROR(row);
    if (!*row) return jobs;
    Result<JobRecord> job = ReadJob(stmt);
    RADFARM_RETURN_IF_ERROR(job);
    jobs.push_back(std::move(*job));
  }
}

std::optional<EventLevel> ParseEventLevel(std::string_view name) {
  for (EventLevel level : {EventLevel::kInfo, EventLevel::kWarning, EventLevel::kError}) {
    if (EventLevelName(level) == name) return level;
  }
  return std::nullopt;
}

}  // namespace

std::string_view EventLevelName(EventLevel level) {
  switch (level) {
    case EventLevel::kInfo:
      return "info";
    case EventLevel::kWarning:
      return "warning";
    case EventLevel::kError:
      return "error";
  }
  return "info";
}

Result<JobStore> JobStore::Open(const std::string& path, JobStoreOptions options) {
  // SQLite would take a 0-byte file as a new, empty database: every job of a store truncated by
  // accident (or a full disk) would be gone without a word. Only a missing file is created.
  std::error_code ec;
  if (std::filesystem::is_regular_file(path, ec) && std::filesystem::file_size(path, ec) == 0 &&
      !ec) {
    return Error{"job store " + path +
                 ": the file is empty (0 bytes), not a job store; refusing to start over in it. "
                 "Restore it from a backup, or delete it to start with no jobs"};
  }
  Result<Database> db = Database::Open(path, options.database);
  RADFARM_RETURN_IF_ERROR(db);
  // Everything up to here only read the file; refuse before the first write.
  RADFARM_RETURN_IF_ERROR(CheckDatabase(*db, options.check));
  // foreign_keys is per connection and cannot change inside a transaction.
  RADFARM_RETURN_IF_ERROR(db->Exec("PRAGMA foreign_keys = ON", "enable foreign keys"));
  Result<std::string> mode = db->QueryText("PRAGMA journal_mode = WAL");
  RADFARM_RETURN_IF_ERROR(mode);
  if (*mode != "wal") {
    return Error{"job store " + path + ": cannot switch to WAL mode (journal_mode is " + *mode +
                 ")"};
  }
  // FULL: in WAL mode a commit is durable only after the WAL is synced; the daemon replies to its
  // peers after commits, so a reply must not outlive a power cut.
  RADFARM_RETURN_IF_ERROR(db->Exec("PRAGMA synchronous = FULL", "set synchronous"));
  if (options.max_pages > 0) {
    // The value is an integer from our options, not text; PRAGMAs cannot be bound.
    RADFARM_RETURN_IF_ERROR(
        db->QueryInt("PRAGMA max_page_count = " + std::to_string(options.max_pages)));
  }
  RADFARM_RETURN_IF_ERROR(Migrate(*db));
  if (!options.now_ms) options.now_ms = SystemNowMs;
  return JobStore(std::move(*db), std::move(options.now_ms));
}

// --- jobs --------------------------------------------------------------------------------------

Result<JobId> JobStore::SubmitJob(const JobSpec& spec) {
  Result<Transaction> transaction = Transaction::Begin(db_);
  RADFARM_RETURN_IF_ERROR(transaction);
  // Checked here for a clearer message than the foreign key's "FOREIGN KEY constraint failed".
  Result<Statement> scene = db_.Prepare("SELECT 1 FROM scenes WHERE hash = ?1");
  RADFARM_RETURN_IF_ERROR(scene);
  scene->Bind(1, spec.scene_hash);
  Result<bool> found = scene->Step();
  RADFARM_RETURN_IF_ERROR(found);
  if (!*found) {
    return Error{"job store " + path() + ": submit job '" + spec.name + "': scene " +
                 spec.scene_hash + " is not stored (PutScene first)"};
  }
  Result<Statement> insert = db_.Prepare(
      "INSERT INTO jobs (name, scene_hash, settings, seed, priority, state, submitted_at_ms) "
      "VALUES (?1, ?2, ?3, ?4, ?5, 'queued', ?6)");
  RADFARM_RETURN_IF_ERROR(insert);
  insert->Bind(1, spec.name)
      .Bind(2, spec.scene_hash)
      .Bind(3, spec.settings)
      .Bind(4, static_cast<int64_t>(spec.seed))
      .Bind(5, spec.priority)
      .Bind(6, now_ms_());
  RADFARM_RETURN_IF_ERROR(insert->Run());
  JobId id = db_.LastInsertRowid();
  RADFARM_RETURN_IF_ERROR(transaction->Commit());
  return id;
}

Result<std::vector<JobRecord>> JobStore::ListJobs() {
  Result<Statement> stmt =
      db_.Prepare("SELECT " + std::string(kJobColumns) + " FROM jobs ORDER BY id");
  RADFARM_RETURN_IF_ERROR(stmt);
  return ReadJobs(*stmt);
}

Result<std::optional<JobRecord>> JobStore::GetJob(JobId id) {
  Result<Statement> stmt =
      db_.Prepare("SELECT " + std::string(kJobColumns) + " FROM jobs WHERE id = ?1");
  RADFARM_RETURN_IF_ERROR(stmt);
  stmt->Bind(1, id);
  Result<std::vector<JobRecord>> jobs = ReadJobs(*stmt);
  RADFARM_RETURN_IF_ERROR(jobs);
  if (jobs->empty()) return std::optional<JobRecord>();
  return std::optional<JobRecord>(std::move(jobs->front()));
}

Status JobStore::SetJobState(JobId id, JobState to, std::optional<std::string> error) {
  std::string job_name = "job " + std::to_string(id);
  if ((to == JobState::kFailed || to == JobState::kHeld) && !error) {
    return Error{"job store: " + job_name + ": a " + std::string(JobStateName(to)) +
                 " job needs an error text"};
  }
  if (error && to != JobState::kFailed && to != JobState::kHeld && to != JobState::kCancelled &&
      to != JobState::kPaused) {
    return Error{"job store: " + job_name +
                 ": an error text only goes with failed, held, cancelled or paused"};
  }
  Result<Transaction> transaction = Transaction::Begin(db_);
  RADFARM_RETURN_IF_ERROR(transaction);
  Result<std::optional<JobRecord>> job = GetJob(id);
  RADFARM_RETURN_IF_ERROR(job);
  if (!job->has_value()) return Error{"job store: " + job_name + " does not exist"};
  JobState from = (*job)->state;
  if (!IsAllowedTransition(from, to)) {
    return Error{"job store: " + job_name + ": illegal state transition " +
                 std::string(JobStateName(from)) + " -> " + std::string(JobStateName(to))};
  }
  int64_t now = now_ms_();
  Result<Statement> update = db_.Prepare(
      "UPDATE jobs SET state = ?2, error = ?3,"
      " started_at_ms = CASE WHEN ?2 = 'running' THEN coalesce(started_at_ms, ?4)"
      "                 ELSE started_at_ms END,"
      " finished_at_ms = CASE WHEN ?5 THEN ?4 ELSE finished_at_ms END"
      " WHERE id = ?1");
  RADFARM_RETURN_IF_ERROR(update);
  update->Bind(1, id).Bind(2, JobStateName(to)).Bind(4, now).Bind(5, int64_t{IsTerminal(to)});
  if (error) {
    update->Bind(3, *error);
  } else {
    update->BindNull(3);
  }
  RADFARM_RETURN_IF_ERROR(update->Run());
  return transaction->Commit();
}

Result<std::vector<JobRecord>> JobStore::NextRunnableJobs(int limit) {
  Result<Statement> stmt = db_.Prepare("SELECT " + std::string(kJobColumns) +
                                       " FROM jobs WHERE state = 'queued'"
                                       " ORDER BY priority DESC, submitted_at_ms, id LIMIT ?1");
  RADFARM_RETURN_IF_ERROR(stmt);
  stmt->Bind(1, int64_t{limit});
  return ReadJobs(*stmt);
}

// --- scenes ------------------------------------------------------------------------------------

Status JobStore::PutScene(const std::string& hash, std::span<const uint8_t> geometry) {
  Result<Transaction> transaction = Transaction::Begin(db_);
  RADFARM_RETURN_IF_ERROR(transaction);
  Result<Statement> insert = db_.Prepare(
      "INSERT INTO scenes (hash, geometry, size, stored_at_ms, checksum)"
      " VALUES (?1, ?2, ?3, ?4, ?5) ON CONFLICT (hash) DO NOTHING");
  RADFARM_RETURN_IF_ERROR(insert);
  insert->Bind(1, hash)
      .BindBlob(2, geometry)
      .Bind(3, static_cast<int64_t>(geometry.size()))
      .Bind(4, now_ms_())
      .BindBlob(5, BlobChecksum(geometry));
  RADFARM_RETURN_IF_ERROR(insert->Run());
  if (db_.Changes() == 0) {
    Result<std::optional<std::vector<uint8_t>>> stored = GetScene(hash);
    RADFARM_RETURN_IF_ERROR(stored);
    if (!stored->has_value() ||
        !std::equal((*stored)->begin(), (*stored)->end(), geometry.begin(), geometry.end())) {
      return Error{"job store: scene " + hash + " is already stored with different bytes"};
    }
  }
  return transaction->Commit();
}

Result<std::optional<std::vector<uint8_t>>> JobStore::GetScene(const std::string& hash) {
  Result<Statement> stmt = db_.Prepare("SELECT geometry, checksum FROM scenes WHERE hash = ?1");
  RADFARM_RETURN_IF_ERROR(stmt);
  stmt->Bind(1, hash);
  Result<bool> row = stmt->Step();
  RADFARM_RETURN_IF_ERROR(row);
  if (!*row) return std::optional<std::vector<uint8_t>>();
  std::vector<uint8_t> geometry = stmt->Blob(0);
  if (!ChecksumMatches(stmt->Blob(1), BlobChecksum(geometry))) {
    return Error{"job store " + path() + ": scene " + hash +
                 " is damaged (its bytes do not match its checksum); restore the store from a "
                 "backup or submit the job again"};
  }
  return std::optional<std::vector<uint8_t>>(std::move(geometry));
}

// --- agents and events -------------------------------------------------------------------------

Status JobStore::RecordAgentSeen(const std::string& name, const std::string& address,
                                 uint32_t threads) {
  Result<Statement> stmt = db_.Prepare(
      "INSERT INTO agents (name, address, threads, first_seen_ms, last_seen_ms)"
      " VALUES (?1, ?2, ?3, ?4, ?4)"
      " ON CONFLICT (name) DO UPDATE SET address = excluded.address,"
      " threads = excluded.threads, last_seen_ms = excluded.last_seen_ms");
  RADFARM_RETURN_IF_ERROR(stmt);
  stmt->Bind(1, name).Bind(2, address).Bind(3, int64_t{threads}).Bind(4, now_ms_());
  return stmt->Run();
}

Result<std::vector<AgentRecord>> JobStore::ListAgents() {
  Result<Statement> stmt = db_.Prepare(
      "SELECT name, address, threads, first_seen_ms, last_seen_ms FROM agents ORDER BY name");
  RADFARM_RETURN_IF_ERROR(stmt);
  std::vector<AgentRecord> agents;
  while (true) {
    Result<bool> row = stmt->Step();
    RADFARM_RETURN_IF_ERROR(row);
    if (!*row) return agents;
    agents.push_back({stmt->Text(0), stmt->Text(1), static_cast<uint32_t>(stmt->Int(2)),
                      stmt->Int(3), stmt->Int(4)});
  }
}

Status JobStore::AppendEvent(std::optional<JobId> job, EventLevel level, const std::string& text) {
  Result<Statement> stmt =
      db_.Prepare("INSERT INTO events (job_id, time_ms, level, text) VALUES (?1, ?2, ?3, ?4)");
  RADFARM_RETURN_IF_ERROR(stmt);
  if (job) {
    stmt->Bind(1, *job);
  } else {
    stmt->BindNull(1);
  }
  stmt->Bind(2, now_ms_()).Bind(3, EventLevelName(level)).Bind(4, text);
  return stmt->Run();
}

namespace {

Result<std::vector<Event>> ReadEvents(Statement& stmt) {
  std::vector<Event> events;
  while (true) {
    Result<bool> row = stmt.Step();
    RADFARM_RETURN_IF_ERROR(row);
    if (!*row) return events;
    Event event;
    event.id = stmt.Int(0);
    event.job = OptionalInt(stmt, 1);
    event.time_ms = stmt.Int(2);
    event.level = ParseEventLevel(stmt.Text(3)).value_or(EventLevel::kInfo);
    event.text = stmt.Text(4);
    events.push_back(std::move(event));
  }
}

}  // namespace

Result<std::vector<Event>> JobStore::ListEvents(std::optional<JobId> job, int limit) {
  // `job_id IS ?1` matches NULL to NULL, so one statement serves farm-wide events too.
  Result<Statement> stmt = db_.Prepare(
      "SELECT id, job_id, time_ms, level, text FROM ("
      "  SELECT * FROM events WHERE job_id IS ?1 ORDER BY id DESC LIMIT ?2"
      ") ORDER BY id");
  RADFARM_RETURN_IF_ERROR(stmt);
  if (job) {
    stmt->Bind(1, *job);
  } else {
    stmt->BindNull(1);
  }
  stmt->Bind(2, int64_t{limit});
  return ReadEvents(*stmt);
}

Result<std::vector<Event>> JobStore::ListRecentEvents(int limit) {
  Result<Statement> stmt = db_.Prepare(
      "SELECT id, job_id, time_ms, level, text FROM ("
      "  SELECT * FROM events ORDER BY id DESC LIMIT ?1"
      ") ORDER BY id");
  RADFARM_RETURN_IF_ERROR(stmt);
  stmt->Bind(1, int64_t{limit});
  return ReadEvents(*stmt);
}

}  // namespace radfarm::store
