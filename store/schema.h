// The store's schema and its evolution. The schema version is PRAGMA user_version; migration k
// (1-based) takes a file from version k-1 to version k. Each migration runs in its own
// transaction together with its user_version bump, so a file is always at exactly one version.
//
// Rules for whoever adds version N+1: append a migration to kMigrations, never edit a published
// one (files in the field are at every earlier version), and extend the v1 fixture test if the
// upgrade must transform data.
//
// The file is marked as ours by PRAGMA application_id = kApplicationId (set by migration 1, in the
// same transaction as the first tables). Open refuses, without writing anything:
//   - a file that is not a SQLite database (SQLITE_NOTADB),
//   - a SQLite database with another application_id, or with id 0 and tables of its own,
//   - a database newer than this build (user_version > kSchemaVersion),
//   - a database that fails the integrity check.
#pragma once

#include <cstdint>
#include <span>
#include <string_view>

#include "base/result.h"
#include "store/database.h"

namespace radfarm::store {

// "RAD1" as a big-endian 32-bit integer: how `file` and sqlite3 identify our files.
inline constexpr int32_t kApplicationId = 0x52414431;

struct Migration {
  int version;           // user_version after this migration
  std::string_view sql;  // fixed SQL, one or more statements
  // It rebuilds a table that others reference (SQLite's way to change a column's constraint: a
  // new table, the rows copied, the old one dropped, the new one renamed). Foreign keys are off
  // around it, so the drop cascades to nothing, and checked (foreign_key_check) before the commit.
  bool rebuilds_referenced_table = false;
};

std::span<const Migration> Migrations();
int LatestSchemaVersion();

struct SchemaCheckOptions {
  // PRAGMA integrity_check (every page, every index entry against its table: O(N log N)) below this
  // file size; PRAGMA quick_check (pages and records, no index cross-check: O(N)) above it. With
  // pruned checkpoints a store stays a few MB, so the full check is the normal case.
  int64_t full_check_max_bytes = 256 << 20;
};

// Checks that `db` is ours (or empty), uncorrupted and not newer than this build. Writes nothing.
// Returns the schema version found (0 for an empty file).
Result<int> CheckDatabase(Database& db, const SchemaCheckOptions& options);

// Applies the migrations from the file's version up to `target` (default: the latest), each in
// its own IMMEDIATE transaction. Version 0 -> 1 also sets the application_id.
Status Migrate(Database& db, int target = -1);

}  // namespace radfarm::store
