#include "store/schema.h"

#include <algorithm>
#include <array>
#include <string>

#include "base/result.h"

namespace radfarm::store {
namespace {

// Version 1: the tables. Times are milliseconds since the Unix epoch (UTC) from the store's clock.
constexpr std::string_view kV1 = R"sql(
CREATE TABLE scenes (
  hash TEXT PRIMARY KEY,
  geometry BLOB NOT NULL,
  size INTEGER NOT NULL CHECK (size >= 0),
  stored_at_ms INTEGER NOT NULL
);
CREATE TABLE jobs (
  id INTEGER PRIMARY KEY,
  name TEXT NOT NULL,
  scene_hash TEXT NOT NULL REFERENCES scenes(hash),
  settings TEXT NOT NULL,
  seed INTEGER NOT NULL,
  priority INTEGER NOT NULL,
  state TEXT NOT NULL
    CHECK (state IN ('queued', 'running', 'paused', 'done', 'failed', 'cancelled')),
  submitted_at_ms INTEGER NOT NULL,
  started_at_ms INTEGER,
  finished_at_ms INTEGER,
  error TEXT
);
CREATE TABLE rounds (
  job_id INTEGER NOT NULL REFERENCES jobs(id) ON DELETE CASCADE,
  round INTEGER NOT NULL CHECK (round >= 0),
  shooters INTEGER NOT NULL,
  rays INTEGER NOT NULL,
  unshot_fraction REAL NOT NULL,
  unshot_power REAL NOT NULL,
  duration_seconds REAL NOT NULL,
  recorded_at_ms INTEGER NOT NULL,
  PRIMARY KEY (job_id, round)
) WITHOUT ROWID;
CREATE TABLE checkpoints (
  job_id INTEGER NOT NULL,
  round INTEGER NOT NULL,
  rounds_done INTEGER NOT NULL,
  patches INTEGER NOT NULL,
  radiosity BLOB NOT NULL CHECK (length(radiosity) = 24 * patches),
  unshot BLOB NOT NULL CHECK (length(unshot) = 24 * patches),
  energy BLOB NOT NULL CHECK (length(energy) = 32),
  created_at_ms INTEGER NOT NULL,
  PRIMARY KEY (job_id, round),
  FOREIGN KEY (job_id, round) REFERENCES rounds(job_id, round) ON DELETE CASCADE
);
CREATE TABLE agents (
  name TEXT PRIMARY KEY,
  address TEXT NOT NULL,
  threads INTEGER NOT NULL,
  first_seen_ms INTEGER NOT NULL,
  last_seen_ms INTEGER NOT NULL
);
CREATE TABLE events (
  id INTEGER PRIMARY KEY,
  job_id INTEGER REFERENCES jobs(id) ON DELETE CASCADE,
  time_ms INTEGER NOT NULL,
  level TEXT NOT NULL CHECK (level IN ('info', 'warning', 'error')),
  text TEXT NOT NULL
);
)sql";

// Version 2: indexes for the scheduler's query (NextRunnableJobs) and per-job event listing.
constexpr std::string_view kV2 = R"sql(
CREATE INDEX jobs_runnable ON jobs (state, priority DESC, submitted_at_ms, id);
CREATE INDEX events_by_job ON events (job_id, id);
)sql";

// Version 3: per-round ray fates, so a resumed job's statistics count every round.
constexpr std::string_view kV3 = R"sql(
ALTER TABLE rounds ADD COLUMN escaped_rays INTEGER NOT NULL DEFAULT 0 CHECK (escaped_rays >= 0);
ALTER TABLE rounds ADD COLUMN back_rays INTEGER NOT NULL DEFAULT 0 CHECK (back_rays >= 0);
)sql";

// Version 4: a checkpoint of a job with adaptive refinement belongs to a refined mesh: the hash of
// its scene blob (stored in scenes; NULL: the mesh the job's bundle makes) and the refinement
// points already passed, so a resumed job neither loses the mesh nor refines twice. And the last
// checkpoint of a solve says why it stopped: a round capped by the ray budget may leave a few rays
// of it unspent, and a solve resumed from it must not plan another round.
constexpr std::string_view kV4 = R"sql(
ALTER TABLE checkpoints ADD COLUMN scene_hash TEXT REFERENCES scenes(hash);
ALTER TABLE checkpoints ADD COLUMN refine_points INTEGER NOT NULL DEFAULT 0
  CHECK (refine_points >= 0);
ALTER TABLE checkpoints ADD COLUMN stop_reason TEXT;
)sql";

// Version 5: checksums (blob_checksum.h) on checkpoints and stored scenes, verified on load. Rows
// from before have none and are read as before.
constexpr std::string_view kV5 = R"sql(
ALTER TABLE checkpoints ADD COLUMN checksum BLOB CHECK (checksum IS NULL OR length(checksum) = 32);
ALTER TABLE scenes ADD COLUMN checksum BLOB CHECK (checksum IS NULL OR length(checksum) = 32);
)sql";

// Version 6: the accepted batch results of a round in progress, so a restarted master re-leases
// only the batches it had not received. Rows of a round go after its checkpoint
// (PruneRoundResults), so the table holds the rounds since a running job's last checkpoint.
constexpr std::string_view kV6 = R"sql(
CREATE TABLE round_results (
  job_id INTEGER NOT NULL REFERENCES jobs(id) ON DELETE CASCADE,
  round INTEGER NOT NULL CHECK (round >= 0),
  batch INTEGER NOT NULL CHECK (batch >= 0),
  shooter INTEGER NOT NULL,
  first_ray INTEGER NOT NULL,
  ray_count INTEGER NOT NULL,
  batch_rays INTEGER NOT NULL,
  result BLOB NOT NULL,
  checksum BLOB NOT NULL CHECK (length(checksum) = 32),
  PRIMARY KEY (job_id, round, batch)
) WITHOUT ROWID;
)sql";

// Version 7: per-agent credentials (protocol/agent_key.h). The key is derived from the farm secret,
// the name and the generation, so no key is stored; enrolling a name again bumps the generation.
constexpr std::string_view kV7 = R"sql(
CREATE TABLE agent_credentials (
  name TEXT PRIMARY KEY,
  generation INTEGER NOT NULL CHECK (generation >= 1),
  revoked INTEGER NOT NULL CHECK (revoked IN (0, 1)),
  enrolled_at_ms INTEGER NOT NULL,
  revoked_at_ms INTEGER
);
)sql";

// Version 8: `held` a job state of its own (job_state.h). Before it a held job was `paused` with
// a reason starting "held: "; such rows become `held` with the rest of the reason. SQLite cannot
// change a CHECK constraint in place, so the jobs table is rebuilt (with its index).
constexpr std::string_view kV8 = R"sql(
CREATE TABLE jobs_v8 (
  id INTEGER PRIMARY KEY,
  name TEXT NOT NULL,
  scene_hash TEXT NOT NULL REFERENCES scenes(hash),
  settings TEXT NOT NULL,
  seed INTEGER NOT NULL,
  priority INTEGER NOT NULL,
  state TEXT NOT NULL
    CHECK (state IN ('queued', 'running', 'paused', 'held', 'done', 'failed', 'cancelled')),
  submitted_at_ms INTEGER NOT NULL,
  started_at_ms INTEGER,
  finished_at_ms INTEGER,
  error TEXT
);
INSERT INTO jobs_v8 (id, name, scene_hash, settings, seed, priority, state, submitted_at_ms,
                     started_at_ms, finished_at_ms, error)
  SELECT id, name, scene_hash, settings, seed, priority,
         CASE WHEN state = 'paused' AND substr(error, 1, 6) = 'held: ' THEN 'held' ELSE state END,
         submitted_at_ms, started_at_ms, finished_at_ms,
         CASE WHEN state = 'paused' AND substr(error, 1, 6) = 'held: ' THEN substr(error, 7)
              ELSE error END
  FROM jobs;
DROP TABLE jobs;
ALTER TABLE jobs_v8 RENAME TO jobs;
CREATE INDEX jobs_runnable ON jobs (state, priority DESC, submitted_at_ms, id);
)sql";

// Version 9: a finished job's display (codec/display_blob.h), drawn by the master from the
// checkpoint of round `round`, so `radfarm fetch` only writes files.
constexpr std::string_view kV9 = R"sql(
CREATE TABLE displays (
  job_id INTEGER PRIMARY KEY REFERENCES jobs(id) ON DELETE CASCADE,
  round INTEGER NOT NULL CHECK (round >= 0),
  display BLOB NOT NULL,
  checksum BLOB NOT NULL CHECK (length(checksum) = 32)
);
)sql";

constexpr std::array<Migration, 9> kMigrations = {{{1, kV1},
                                                   {2, kV2},
                                                   {3, kV3},
                                                   {4, kV4},
                                                   {5, kV5},
                                                   {6, kV6},
                                                   {7, kV7},
                                                   {8, kV8, /*rebuilds_referenced_table=*/true},
                                                   {9, kV9}}};

Result<int64_t> FileBytes(Database& db) {
  Result<int64_t> pages = db.QueryInt("PRAGMA page_count");
  RADFARM_RETURN_IF_ERROR(pages);
  Result<int64_t> page_size = db.QueryInt("PRAGMA page_size");
  RADFARM_RETURN_IF_ERROR(page_size);
  return *pages * *page_size;
}

Status CheckIntegrity(Database& db, const SchemaCheckOptions& options) {
  Result<int64_t> bytes = FileBytes(db);
  RADFARM_RETURN_IF_ERROR(bytes);
  bool full = *bytes <= options.full_check_max_bytes;
  Result<Statement> check =
      db.Prepare(full ? "PRAGMA integrity_check(20)" : "PRAGMA quick_check(20)");
  RADFARM_RETURN_IF_ERROR(check);
  std::string problems;
  while (true) {
    Result<bool> row = check->Step();
    RADFARM_RETURN_IF_ERROR(row);
    if (!*row) break;
    std::string line = check->Text(0);
    if (line == "ok") continue;
    std::replace(line.begin(), line.end(), '\n', ' ');  // keep the error one line
    if (!problems.empty()) problems += "; ";
    problems += line;
  }
  if (problems.empty()) return Ok{};
  return Error{
      "job store " + db.path() + ": SQLITE_CORRUPT: " + (full ? "integrity_check" : "quick_check") +
          " failed; the file was left untouched: restore it from a backup (" + problems + ")",
      ErrorKind::kCorrupt};
}

// One migration and its user_version bump in one IMMEDIATE transaction.
Status ApplyMigration(Database& db, const Migration& migration) {
  Result<Transaction> transaction = Transaction::Begin(db);
  RADFARM_RETURN_IF_ERROR(transaction);
  // Read again under the write lock: another process opening the same new file (`radfarm
  // render --db` and a reader of its store) may have migrated it since the caller's read.
  Result<int64_t> locked = db.QueryInt("PRAGMA user_version");
  RADFARM_RETURN_IF_ERROR(locked);
  if (*locked >= migration.version) return Ok{};  // the transaction rolls back: nothing written
  std::string what = "migration to schema version " + std::to_string(migration.version);
  Status applied = db.Exec(migration.sql, what);
  RADFARM_RETURN_IF_ERROR(applied);
  if (migration.rebuilds_referenced_table) {
    // With foreign keys off nothing checked the copied rows; a dangling reference fails here.
    Result<Statement> check = db.Prepare("PRAGMA foreign_key_check");
    RADFARM_RETURN_IF_ERROR(check);
    Result<bool> dangling = check->Step();
    RADFARM_RETURN_IF_ERROR(dangling);
    if (*dangling) {
      return Error{"job store " + db.path() + ": " + what + ": table " + check->Text(0) +
                   " holds a reference to a missing row of " + check->Text(2) +
                   "; the file was left untouched"};
    }
  }
  // PRAGMAs take no bound parameters; both values are this build's own constants.
  std::string pragmas = "PRAGMA user_version = " + std::to_string(migration.version) + ";";
  if (migration.version == 1) {
    pragmas += "PRAGMA application_id = " + std::to_string(kApplicationId) + ";";
  }
  Status bumped = db.Exec(pragmas, what);
  RADFARM_RETURN_IF_ERROR(bumped);
  return transaction->Commit();
}

}  // namespace

std::span<const Migration> Migrations() { return kMigrations; }
int LatestSchemaVersion() { return kMigrations.back().version; }

Result<int> CheckDatabase(Database& db, const SchemaCheckOptions& options) {
  // The first read of the header: garbage gives SQLITE_NOTADB here.
  Result<int64_t> app_id = db.QueryInt("PRAGMA application_id");
  RADFARM_RETURN_IF_ERROR(app_id);
  Result<int64_t> objects = db.QueryInt("SELECT count(*) FROM sqlite_schema");
  RADFARM_RETURN_IF_ERROR(objects);
  if (*app_id != kApplicationId && (*app_id != 0 || *objects != 0)) {
    return Error{"job store " + db.path() +
                 ": a SQLite database of another program (application_id " +
                 std::to_string(*app_id) + ", radfarm uses " + std::to_string(kApplicationId) +
                 "); refusing to touch it"};
  }
  Result<int64_t> version = db.QueryInt("PRAGMA user_version");
  RADFARM_RETURN_IF_ERROR(version);
  if (*version > LatestSchemaVersion()) {
    return Error{"job store " + db.path() + ": schema version " + std::to_string(*version) +
                 " is newer than this build knows (" + std::to_string(LatestSchemaVersion()) +
                 "); upgrade radfarm, the file was left untouched"};
  }
  Status integrity = CheckIntegrity(db, options);
  RADFARM_RETURN_IF_ERROR(integrity);
  return static_cast<int>(*version);
}

Status Migrate(Database& db, int target) {
  if (target < 0) target = LatestSchemaVersion();
  Result<int64_t> current = db.QueryInt("PRAGMA user_version");
  RADFARM_RETURN_IF_ERROR(current);
  for (const Migration& migration : kMigrations) {
    if (migration.version <= *current || migration.version > target) continue;
    if (!migration.rebuilds_referenced_table) {
      RADFARM_RETURN_IF_ERROR(ApplyMigration(db, migration));
      continue;
    }
    // PRAGMA foreign_keys is a no-op inside a transaction: it is turned off around it.
    Result<int64_t> foreign_keys = db.QueryInt("PRAGMA foreign_keys");
    RADFARM_RETURN_IF_ERROR(foreign_keys);
    RADFARM_RETURN_IF_ERROR(db.Exec("PRAGMA foreign_keys = OFF", "disable foreign keys"));
    const Status applied = ApplyMigration(db, migration);
    const Status restored =
        db.Exec(*foreign_keys != 0 ? "PRAGMA foreign_keys = ON" : "PRAGMA foreign_keys = OFF",
                "restore foreign keys");
    RADFARM_RETURN_IF_ERROR(applied);
    RADFARM_RETURN_IF_ERROR(restored);
  }
  return Ok{};
}

}  // namespace radfarm::store
