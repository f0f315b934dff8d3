// Translation of SQLite result codes into store errors: the one place where SQLite's codes become
// radfarm messages. A message names the database file, what the store was doing, the code's name
// (SQLITE_BUSY, SQLITE_CORRUPT, ...) and what an operator can do about it, e.g.
//   "job store /var/lib/radfarm/jobs.db: save checkpoint: SQLITE_FULL: disk full or size limit
//    reached (database or disk is full); free space, nothing was written"
#pragma once

#include <string>
#include <string_view>

#include "base/result.h"

struct sqlite3;

namespace radfarm::store {

// Name of a primary or extended result code, e.g. "SQLITE_IOERR_WRITE"; "SQLITE_<n>" if unknown.
std::string SqliteCodeName(int code);

// The kind of a primary or extended result code: SQLITE_FULL is kDiskFull, SQLITE_IOERR_* kIo
// (but SQLITE_IOERR_NOMEM, memory, kOther), SQLITE_BUSY and SQLITE_LOCKED kBusy, SQLITE_CORRUPT
// and SQLITE_NOTADB kCorrupt, SQLITE_CONSTRAINT_* kConstraint, anything else kOther.
ErrorKind SqliteErrorKind(int code);

// Builds the store error for `code` (an extended code when available) raised while doing `what`,
// of kind SqliteErrorKind(code). `db` may be null (open failed before a handle existed); its
// sqlite3_errmsg() is appended when set.
Error SqliteError(std::string_view path, std::string_view what, int code, sqlite3* db);

// Whether an error of `kind` is a fault of the disk under the store that may pass (disk full or
// the store's size limit, an I/O error) rather than of the request: the master holds a job that
// meets one instead of failing it.
bool IsStoreFault(ErrorKind kind);

}  // namespace radfarm::store
