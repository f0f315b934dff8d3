#include "store/sqlite_error.h"

#include <sqlite3.h>

namespace radfarm::store {
namespace {

// What an operator should know about the codes the store can meet in normal operation.
std::string_view Advice(int primary) {
  switch (primary) {
    case SQLITE_BUSY:
    case SQLITE_LOCKED:
      return "the database is locked by another connection (is another radfarmd using this file?)";
    case SQLITE_CORRUPT:
      return "the database file is corrupt; it was left untouched: restore it from a backup";
    case SQLITE_NOTADB:
      return "the file is not a SQLite database (a file of another program?); it was left "
             "untouched";
    case SQLITE_FULL:
      return "disk full or database size limit reached; the transaction was rolled back";
    case SQLITE_IOERR:
      return "I/O error reading or writing the database; the transaction was rolled back";
    case SQLITE_CANTOPEN:
      return "cannot open the database file (missing directory, a directory path, or permissions)";
    case SQLITE_READONLY:
      return "the database is read-only";
    case SQLITE_PERM:
    case SQLITE_AUTH:
      return "permission denied";
    case SQLITE_CONSTRAINT:
      return "a constraint was violated";
    case SQLITE_NOMEM:
      return "out of memory";
    default:
      return "";
  }
}

}  // namespace

std::string SqliteCodeName(int code) {
  // sqlite3_errstr() gives prose only; the names are what operators search for.
  std::string name;
  switch (code & 0xff) {
    case SQLITE_ERROR:
      name = "SQLITE_ERROR";
      break;
    case SQLITE_BUSY:
      name = "SQLITE_BUSY";
      break;
    case SQLITE_LOCKED:
      name = "SQLITE_LOCKED";
      break;
    case SQLITE_NOMEM:
      name = "SQLITE_NOMEM";
      break;
    case SQLITE_READONLY:
      name = "SQLITE_READONLY";
      break;
    case SQLITE_IOERR:
      name = "SQLITE_IOERR";
      break;
    case SQLITE_CORRUPT:
      name = "SQLITE_CORRUPT";
      break;
    case SQLITE_FULL:
      name = "SQLITE_FULL";
      break;
    case SQLITE_CANTOPEN:
      name = "SQLITE_CANTOPEN";
      break;
    case SQLITE_CONSTRAINT:
      name = "SQLITE_CONSTRAINT";
      break;
    case SQLITE_MISMATCH:
      name = "SQLITE_MISMATCH";
      break;
    case SQLITE_NOTADB:
      name = "SQLITE_NOTADB";
      break;
    case SQLITE_PERM:
      name = "SQLITE_PERM";
      break;
    case SQLITE_AUTH:
      name = "SQLITE_AUTH";
      break;
    case SQLITE_RANGE:
      name = "SQLITE_RANGE";
      break;
    default:
      return "SQLITE_" + std::to_string(code);
  }
  // Extended codes (e.g. SQLITE_IOERR_WRITE) keep their number for the SQLite documentation.
  if (code > 0xff) name += " (extended code " + std::to_string(code) + ")";
  return name;
}

ErrorKind SqliteErrorKind(int code) {
  if (code == SQLITE_IOERR_NOMEM) return ErrorKind::kOther;  // memory, not the disk
  switch (code & 0xff) {
    case SQLITE_FULL:
      return ErrorKind::kDiskFull;
    case SQLITE_IOERR:
      return ErrorKind::kIo;
    case SQLITE_BUSY:
    case SQLITE_LOCKED:
      return ErrorKind::kBusy;
    case SQLITE_CORRUPT:
    case SQLITE_NOTADB:
      return ErrorKind::kCorrupt;
    case SQLITE_CONSTRAINT:
      return ErrorKind::kConstraint;
    default:
      return ErrorKind::kOther;
  }
}

Error SqliteError(std::string_view path, std::string_view what, int code, sqlite3* db) {
  std::string message = "job store ";
  message += path;
  message += ": ";
  message += what;
  message += ": ";
  message += SqliteCodeName(code);
  std::string_view advice = Advice(code & 0xff);
  if (!advice.empty()) {
    message += ": ";
    message += advice;
  }
  message += " (";
  message += db != nullptr ? sqlite3_errmsg(db) : sqlite3_errstr(code);
  message += ")";
  return Error{std::move(message), SqliteErrorKind(code)};
}

bool IsStoreFault(ErrorKind kind) {
  switch (kind) {
    case ErrorKind::kDiskFull:
    case ErrorKind::kIo:
      return true;
    // A lock held by another connection, damage and broken rules do not pass by waiting; the
    // job fails with the error.
    case ErrorKind::kBusy:
    case ErrorKind::kCorrupt:
    case ErrorKind::kConstraint:
    case ErrorKind::kOther:
      return false;
  }
  return false;
}

}  // namespace radfarm::store
