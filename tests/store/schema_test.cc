// Opening files: migrations from every version, and refusals (corrupt, foreign, newer files).
#include "store/schema.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <thread>

#include "store/job_store.h"
#include "tests/store/temp_dir.h"

namespace radfarm::store {
namespace {

Database OpenRaw(const std::string& path) {
  Result<Database> db = Database::Open(path, {});
  EXPECT_TRUE(db.ok()) << db.error();
  return std::move(*db);
}

// The schema as text (tables and indexes), to compare an upgraded file with a fresh one.
std::string SchemaText(Database& db) {
  Result<Statement> stmt =
      db.Prepare("SELECT type, name, sql FROM sqlite_schema ORDER BY type, name");
  EXPECT_TRUE(stmt.ok());
  std::string text;
  while (*stmt->Step()) text += stmt->Text(0) + " " + stmt->Text(1) + ": " + stmt->Text(2) + "\n";
  return text;
}

int64_t UserVersion(const std::string& path) {
  Database db = OpenRaw(path);
  return *db.QueryInt("PRAGMA user_version");
}

void ExpectRefused(const std::string& path, const std::string& expected,
                   ErrorKind kind = ErrorKind::kOther) {
  std::vector<uint8_t> before = ReadBytes(path);
  Result<JobStore> store = JobStore::Open(path);
  ASSERT_FALSE(store.ok());
  EXPECT_EQ(store.error_kind(), kind) << store.error();
  std::printf("refused as expected: %s\n", store.error().c_str());
  EXPECT_NE(store.error().find(expected), std::string::npos) << store.error();
  EXPECT_NE(store.error().find(path), std::string::npos) << store.error();
  // Never a silent overwrite: the refused file keeps every byte.
  EXPECT_EQ(ReadBytes(path), before);
}

TEST(SchemaTest, MigrationVersionsAreConsecutive) {
  int expected = 1;
  for (const Migration& migration : Migrations()) EXPECT_EQ(migration.version, expected++);
  EXPECT_EQ(LatestSchemaVersion(), static_cast<int>(Migrations().size()));
}

// (An existing empty file is refused: rot_test.cc.)
TEST(SchemaTest, CreatesLatestSchemaInANewFile) {
  TempDir dir;
  {
    Result<JobStore> store = JobStore::Open(dir.File("new.db"));
    ASSERT_TRUE(store.ok()) << store.error();
  }
  Database db = OpenRaw(dir.File("new.db"));
  EXPECT_EQ(*db.QueryInt("PRAGMA user_version"), LatestSchemaVersion());
  EXPECT_EQ(*db.QueryInt("PRAGMA application_id"), kApplicationId);
  EXPECT_EQ(*db.QueryText("PRAGMA journal_mode"), "wal");
}

// Walks every version in the list: a file left at version k by an older build upgrades to the
// latest, and ends with exactly the schema of a file created fresh.
TEST(SchemaTest, UpgradesFromEveryEarlierVersion) {
  TempDir dir;
  ASSERT_TRUE(JobStore::Open(dir.File("fresh.db")).ok());
  Database fresh = OpenRaw(dir.File("fresh.db"));
  std::string latest_schema = SchemaText(fresh);
  // From version 1: a file at version 0 is an empty file, which is refused (rot_test.cc).
  for (int k = 1; k <= LatestSchemaVersion(); ++k) {
    SCOPED_TRACE("from version " + std::to_string(k));
    std::string path = dir.File("v" + std::to_string(k) + ".db");
    {
      Database db = OpenRaw(path);
      ASSERT_TRUE(Migrate(db, k).ok());
      EXPECT_EQ(*db.QueryInt("PRAGMA user_version"), k);
    }
    Result<JobStore> store = JobStore::Open(path);
    ASSERT_TRUE(store.ok()) << store.error();
    Database db = OpenRaw(path);
    EXPECT_EQ(*db.QueryInt("PRAGMA user_version"), LatestSchemaVersion());
    EXPECT_EQ(SchemaText(db), latest_schema);
  }
}

// A frozen file from schema version 1 (data/schema_v1.sql) keeps its data through the upgrade.
TEST(SchemaTest, UpgradesVersion1FixtureWithItsData) {
  TempDir dir;
  std::string path = dir.File("v1.db");
  {
    std::ifstream in(std::string(RADFARM_SOURCE_DIR) + "/tests/store/data/schema_v1.sql");
    std::stringstream sql;
    sql << in.rdbuf();
    Database db = OpenRaw(path);
    ASSERT_TRUE(db.Exec(sql.str(), "load fixture").ok());
    ASSERT_EQ(*db.QueryInt("PRAGMA user_version"), 1);
  }
  Result<JobStore> store = JobStore::Open(path);
  ASSERT_TRUE(store.ok()) << store.error();
  EXPECT_EQ(UserVersion(path), LatestSchemaVersion());

  Result<std::optional<JobRecord>> job = store->GetJob(1);
  ASSERT_TRUE(job.ok() && job->has_value());
  EXPECT_EQ((*job)->spec.name, "cornell");
  EXPECT_EQ((*job)->spec.seed, 42u);
  EXPECT_EQ((*job)->state, JobState::kRunning);
  Result<std::vector<JobRecord>> runnable = store->NextRunnableJobs(10);
  ASSERT_TRUE(runnable.ok());
  ASSERT_EQ(runnable->size(), 1u);
  EXPECT_EQ(runnable->front().id, 2);

  Result<std::optional<Checkpoint>> checkpoint = store->LoadLatestCheckpoint(1);
  ASSERT_TRUE(checkpoint.ok() && checkpoint->has_value()) << checkpoint.error();
  EXPECT_EQ((*checkpoint)->radiosity, std::vector<Rgb>{Rgb(1.0, 0.5, 0.25)});
  EXPECT_TRUE(std::signbit((*checkpoint)->unshot[0].g));  // -0.0 survived
  EXPECT_EQ((*checkpoint)->unshot[0].b, 1e308);
  EXPECT_EQ((*checkpoint)->energy.emitted, 2.0);
  EXPECT_FALSE((*checkpoint)->scene_hash.has_value());  // version 4: the bundle's mesh
  EXPECT_EQ((*checkpoint)->refine_points, 0u);
  Result<std::optional<std::vector<uint8_t>>> scene = store->GetScene("sha256:cornell");
  ASSERT_TRUE(scene.ok() && scene->has_value());
  EXPECT_EQ(**scene, (std::vector<uint8_t>{1, 2, 3, 4, 5}));
  EXPECT_EQ(store->ListEvents(1, 10)->size(), 1u);
  EXPECT_EQ(store->ListAgents()->size(), 1u);
}

// Version 3 -> 4: checkpoints written before adaptive refinement reached the farm keep their
// values and read as checkpoints of the bundle's mesh with no refinement point passed; after the
// upgrade a checkpoint names its refined scene, which must be stored.
TEST(SchemaTest, UpgradesVersion3CheckpointsToVersion4) {
  TempDir dir;
  std::string path = dir.File("v3.db");
  {
    Database db = OpenRaw(path);
    ASSERT_TRUE(Migrate(db, 3).ok());
    // What a version 3 build wrote: one job, its round 4 and the checkpoint of it (one patch).
    std::string blob24 = "x'" + std::string(48, '1') + "'";
    std::string blob32 = "x'" + std::string(64, '2') + "'";
    ASSERT_TRUE(db.Exec("INSERT INTO scenes VALUES ('bundle', x'0102', 2, 1);"
                        "INSERT INTO jobs (name, scene_hash, settings, seed, priority, state,"
                        " submitted_at_ms) VALUES ('j', 'bundle', '{}', 7, 0, 'running', 1);"
                        "INSERT INTO rounds VALUES (1, 4, 3, 1000, 0.5, 1.0, 0.25, 2, 11, 12);"
                        "INSERT INTO checkpoints VALUES (1, 4, 5, 1, " +
                            blob24 + ", " + blob24 + ", " + blob32 + ", 3);",
                        "version 3 data")
                    .ok());
  }
  Result<JobStore> store = JobStore::Open(path);
  ASSERT_TRUE(store.ok()) << store.error();
  EXPECT_EQ(UserVersion(path), LatestSchemaVersion());
  // Written before version 5: no checksum, read unverified as before.
  Result<std::optional<Checkpoint>> old = store->LoadLatestCheckpoint(1);
  ASSERT_TRUE(old.ok() && old->has_value()) << old.error();
  EXPECT_EQ((*old)->round, 4u);
  EXPECT_EQ((*old)->rounds_done, 5u);
  ASSERT_EQ((*old)->radiosity.size(), 1u);
  EXPECT_FALSE((*old)->scene_hash.has_value());
  EXPECT_EQ((*old)->refine_points, 0u);
  EXPECT_FALSE((*old)->stop_reason.has_value());
  EXPECT_EQ(store->ListRounds(1)->at(0).back_rays, 12u);

  Checkpoint refined = **old;
  refined.round = 5;
  refined.scene_hash = "refined";
  refined.refine_points = 2;
  refined.stop_reason = "ray budget";
  const RoundRecord round{1, 5, 3, 1000, 0.05, 0.1, 0.25, 0, 0};
  Status missing = store->SaveCheckpoint(round, refined);
  ASSERT_FALSE(missing.ok());  // the refined scene is not stored: nothing is written
  EXPECT_NE(missing.error().find("SQLITE_CONSTRAINT"), std::string::npos) << missing.error();
  EXPECT_EQ(missing.error_kind(), ErrorKind::kConstraint);
  EXPECT_EQ(store->ListRounds(1)->size(), 1u);
  ASSERT_TRUE(store->PutScene("refined", std::vector<uint8_t>{9, 9}).ok());
  ASSERT_TRUE(store->SaveCheckpoint(round, refined).ok());
  Result<std::optional<Checkpoint>> now = store->LoadLatestCheckpoint(1);
  ASSERT_TRUE(now.ok() && now->has_value()) << now.error();
  EXPECT_EQ((*now)->round, 5u);
  EXPECT_EQ((*now)->scene_hash, std::optional<std::string>("refined"));
  EXPECT_EQ((*now)->refine_points, 2u);
  EXPECT_EQ((*now)->stop_reason, std::optional<std::string>("ray budget"));
  EXPECT_EQ((*now)->radiosity, (*old)->radiosity);
}

// Version 7 -> 8: a job held before `held` was a state of its own was `paused` with a reason
// starting "held: "; it comes out `held` with the rest of the reason. Every other row keeps its
// state and reason, and the rebuilt jobs table takes none of the rows referencing it along.
TEST(SchemaTest, UpgradesVersion7HeldJobsToTheHeldState) {
  TempDir dir;
  std::string path = dir.File("v7.db");
  {
    Database db = OpenRaw(path);
    ASSERT_TRUE(db.Exec("PRAGMA foreign_keys = ON", "foreign keys").ok());  // as JobStore opens
    ASSERT_TRUE(Migrate(db, 7).ok());
    ASSERT_TRUE(db.Exec("INSERT INTO scenes VALUES ('bundle', x'0102', 2, 1, NULL);"
                        "INSERT INTO jobs (name, scene_hash, settings, seed, priority, state,"
                        " submitted_at_ms, error) VALUES"
                        " ('held', 'bundle', '{}', 7, 3, 'paused', 1,"
                        "  'held: cannot save the checkpoint: SQLITE_FULL'),"
                        " ('paused', 'bundle', '{}', 8, 0, 'paused', 2, 'by the operator'),"
                        " ('plain', 'bundle', '{}', 9, 0, 'paused', 3, NULL),"
                        " ('failed', 'bundle', '{}', 10, 0, 'failed', 4, 'held: not a hold'),"
                        " ('queued', 'bundle', '{}', 11, 0, 'queued', 5, NULL);"
                        "INSERT INTO rounds (job_id, round, shooters, rays, unshot_fraction,"
                        " unshot_power, duration_seconds, recorded_at_ms)"
                        " VALUES (1, 0, 3, 1000, 0.5, 1.0, 0.25, 6);"
                        "INSERT INTO events (job_id, time_ms, level, text)"
                        " VALUES (1, 7, 'warning', 'held: cannot save the checkpoint');",
                        "version 7 data")
                    .ok());
  }
  Result<JobStore> store = JobStore::Open(path);
  ASSERT_TRUE(store.ok()) << store.error();
  EXPECT_EQ(UserVersion(path), LatestSchemaVersion());

  Result<std::vector<JobRecord>> jobs = store->ListJobs();
  ASSERT_TRUE(jobs.ok()) << jobs.error();
  ASSERT_EQ(jobs->size(), 5u);
  const std::vector<std::pair<JobState, std::optional<std::string>>> expected = {
      {JobState::kHeld, "cannot save the checkpoint: SQLITE_FULL"},
      {JobState::kPaused, "by the operator"},
      {JobState::kPaused, std::nullopt},
      {JobState::kFailed, "held: not a hold"},
      {JobState::kQueued, std::nullopt},
  };
  for (size_t i = 0; i < expected.size(); ++i) {
    SCOPED_TRACE((*jobs)[i].spec.name);
    EXPECT_EQ((*jobs)[i].id, JobId(i + 1));
    EXPECT_EQ((*jobs)[i].state, expected[i].first);
    EXPECT_EQ((*jobs)[i].error, expected[i].second);
  }
  EXPECT_EQ((*jobs)[0].spec.priority, 3);
  EXPECT_EQ((*jobs)[0].spec.seed, 7u);
  EXPECT_EQ(store->ListRounds(1)->size(), 1u);
  EXPECT_EQ(store->ListEvents(1, 10)->size(), 1u);
  // The runnable index came back with the table: the queued job is the one to start.
  Result<std::vector<JobRecord>> runnable = store->NextRunnableJobs(10);
  ASSERT_TRUE(runnable.ok()) << runnable.error();
  ASSERT_EQ(runnable->size(), 1u);
  EXPECT_EQ(runnable->front().id, 5);
}

// The rebuild runs with foreign keys off; the connection gets its setting back either way.
TEST(SchemaTest, ARebuildingMigrationRestoresTheConnectionsForeignKeys) {
  TempDir dir;
  for (int setting : {0, 1}) {
    SCOPED_TRACE("foreign_keys " + std::to_string(setting));
    Database db = OpenRaw(dir.File("fk" + std::to_string(setting) + ".db"));
    ASSERT_TRUE(db.Exec("PRAGMA foreign_keys = " + std::to_string(setting), "set").ok());
    ASSERT_TRUE(Migrate(db).ok());
    EXPECT_EQ(*db.QueryInt("PRAGMA foreign_keys"), setting);
  }
}

// `radfarm render --db` creating its store while a reader opens it: whoever migrates second finds
// the work done (the version is read again under the write lock) instead of failing on it.
TEST(SchemaTest, TwoConnectionsMigratingOneNewFileBothSucceed) {
  TempDir dir;
  for (int i = 0; i < 40; ++i) {
    const std::string path = dir.File("race-" + std::to_string(i) + ".db");
    Database a = OpenRaw(path), b = OpenRaw(path);
    Status migrated_b = Ok{};
    std::thread other([&] { migrated_b = Migrate(b); });
    const Status migrated_a = Migrate(a);
    other.join();
    ASSERT_TRUE(migrated_a.ok()) << migrated_a.error();
    ASSERT_TRUE(migrated_b.ok()) << migrated_b.error();
    EXPECT_EQ(*a.QueryInt("PRAGMA user_version"), LatestSchemaVersion());
  }
}

TEST(SchemaTest, RefusesNewerSchemaVersion) {
  TempDir dir;
  std::string path = dir.File("newer.db");
  ASSERT_TRUE(JobStore::Open(path).ok());
  {
    Database db = OpenRaw(path);
    std::string bump = "PRAGMA user_version = " + std::to_string(LatestSchemaVersion() + 1);
    ASSERT_TRUE(db.Exec(bump, "bump").ok());
  }
  ExpectRefused(path, "is newer than this build knows");
}

TEST(SchemaTest, RefusesFileThatIsNotSqlite) {
  TempDir dir;
  std::string path = dir.File("notes.txt");
  std::string text;
  for (int i = 0; i < 200; ++i) text += "radfarm render scenes/cornell-box.toml --out out/\n";
  WriteBytes(path, std::vector<uint8_t>(text.begin(), text.end()));
  ExpectRefused(path, "SQLITE_NOTADB", ErrorKind::kCorrupt);
}

TEST(SchemaTest, RefusesSqliteDatabaseOfAnotherProgram) {
  TempDir dir;
  std::string with_tables = dir.File("other.db");
  std::string with_id = dir.File("other_id.db");
  {
    Database db = OpenRaw(with_tables);
    ASSERT_TRUE(db.Exec("CREATE TABLE photos (id INTEGER PRIMARY KEY, jpeg BLOB)", "x").ok());
    Database id = OpenRaw(with_id);
    ASSERT_TRUE(id.Exec("PRAGMA application_id = 1234", "x").ok());
  }
  ExpectRefused(with_tables, "a SQLite database of another program");
  ExpectRefused(with_id, "application_id 1234");
}

TEST(SchemaTest, RefusesCorruptFile) {
  TempDir dir;
  std::string path = dir.File("corrupt.db");
  {
    Result<JobStore> store = JobStore::Open(path);
    ASSERT_TRUE(store.ok()) << store.error();
    for (int i = 0; i < 20; ++i) {
      std::vector<uint8_t> geometry(3000, static_cast<uint8_t>(i));
      ASSERT_TRUE(store->PutScene("scene-" + std::to_string(i), geometry).ok());
      ASSERT_TRUE(store->AppendEvent(std::nullopt, EventLevel::kInfo, "event").ok());
    }
  }
  // Closing the last connection checkpoints the WAL into the file: all pages are in the file.
  std::vector<uint8_t> bytes = ReadBytes(path);
  const size_t page = 4096;
  ASSERT_GT(bytes.size(), 8 * page);
  uint32_t state = 12345;
  for (size_t i = page; i < 5 * page; ++i) {  // pages 2 to 5; page 1 (the header) stays valid
    state = state * 1103515245u + 12345u;
    bytes[i] = static_cast<uint8_t>(state >> 16);
  }
  WriteBytes(path, bytes);
  ExpectRefused(path, "SQLITE_CORRUPT", ErrorKind::kCorrupt);
}

}  // namespace
}  // namespace radfarm::store
