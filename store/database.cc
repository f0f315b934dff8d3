#include "store/database.h"

#include <sqlite3.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>
#include <utility>

#include "base/result.h"
#include "store/sqlite_error.h"

namespace radfarm::store {

// --- Database ----------------------------------------------------------------------------------

Result<Database> Database::Open(const std::string& path, const DatabaseOptions& options) {
  int flags = SQLITE_OPEN_READWRITE | SQLITE_OPEN_NOMUTEX;
  if (options.create) flags |= SQLITE_OPEN_CREATE;
  // A new database is its owner's alone whatever the umask; SQLite gives its -wal and -shm files
  // the database's permissions.
  const bool made = options.create && access(path.c_str(), F_OK) != 0;
  sqlite3* db = nullptr;
  int rc = sqlite3_open_v2(path.c_str(), &db, flags,
                           options.vfs.empty() ? nullptr : options.vfs.c_str());
  if (rc != SQLITE_OK) {
    // Even a failed open returns a handle (or null on out-of-memory); it must be closed.
    Error error = SqliteError(path, "open", db != nullptr ? sqlite3_extended_errcode(db) : rc, db);
    sqlite3_close_v2(db);
    return error;
  }
  if (made && chmod(path.c_str(), 0600) != 0 && errno != ENOENT) {
    Error error{path + ": cannot make it private: " + std::strerror(errno)};
    sqlite3_close_v2(db);
    return error;
  }
  sqlite3_extended_result_codes(db, 1);
  sqlite3_busy_timeout(db, options.busy_timeout_ms);
  return Database(db, path);
}

Database::~Database() {
  if (db_ != nullptr) sqlite3_close_v2(db_);
}

Database::Database(Database&& other) noexcept
    : db_(std::exchange(other.db_, nullptr)), path_(std::move(other.path_)) {}

Database& Database::operator=(Database&& other) noexcept {
  if (this != &other) {
    if (db_ != nullptr) sqlite3_close_v2(db_);
    db_ = std::exchange(other.db_, nullptr);
    path_ = std::move(other.path_);
  }
  return *this;
}

Error Database::ErrorFor(std::string_view what, int code) const {
  return SqliteError(path_, what, code, db_);
}

Status Database::Exec(std::string_view sql, std::string_view what) {
  std::string text(sql);
  int rc = sqlite3_exec(db_, text.c_str(), nullptr, nullptr, nullptr);
  if (rc != SQLITE_OK) return ErrorFor(what, sqlite3_extended_errcode(db_));
  return Ok{};
}

Result<Statement> Database::Prepare(std::string_view sql) {
  sqlite3_stmt* stmt = nullptr;
  int rc = sqlite3_prepare_v2(db_, sql.data(), static_cast<int>(sql.size()), &stmt, nullptr);
  if (rc != SQLITE_OK) {
    sqlite3_finalize(stmt);
    return ErrorFor("prepare \"" + std::string(sql.substr(0, 60)) + "\"",
                    sqlite3_extended_errcode(db_));
  }
  return Statement(db_, stmt);
}

Result<int64_t> Database::QueryInt(std::string_view sql) {
  Result<Statement> stmt = Prepare(sql);
  RADFARM_RETURN_IF_ERROR(stmt);
  Result<bool> row = stmt->Step();
  RADFARM_RETURN_IF_ERROR(row);
  if (!*row) return ErrorFor(sql, SQLITE_MISMATCH);
  return stmt->Int(0);
}

Result<std::string> Database::QueryText(std::string_view sql) {
  Result<Statement> stmt = Prepare(sql);
  RADFARM_RETURN_IF_ERROR(stmt);
  Result<bool> row = stmt->Step();
  RADFARM_RETURN_IF_ERROR(row);
  if (!*row) return ErrorFor(sql, SQLITE_MISMATCH);
  return stmt->Text(0);
}

int64_t Database::Changes() const { return sqlite3_changes64(db_); }
int64_t Database::LastInsertRowid() const { return sqlite3_last_insert_rowid(db_); }
bool Database::InTransaction() const { return sqlite3_get_autocommit(db_) == 0; }

// --- Statement ---------------------------------------------------------------------------------

Statement::~Statement() { sqlite3_finalize(stmt_); }

Statement::Statement(Statement&& other) noexcept
    : db_(std::exchange(other.db_, nullptr)),
      stmt_(std::exchange(other.stmt_, nullptr)),
      bind_error_(std::exchange(other.bind_error_, 0)) {}

Statement& Statement::operator=(Statement&& other) noexcept {
  if (this != &other) {
    sqlite3_finalize(stmt_);
    db_ = std::exchange(other.db_, nullptr);
    stmt_ = std::exchange(other.stmt_, nullptr);
    bind_error_ = std::exchange(other.bind_error_, 0);
  }
  return *this;
}

Error Statement::ErrorFor(int code) const {
  const char* sql = sqlite3_sql(stmt_);
  std::string what = sql != nullptr ? std::string(sql).substr(0, 60) : std::string("statement");
  const char* file = sqlite3_db_filename(db_, "main");
  return SqliteError(file != nullptr ? file : "", "\"" + what + "\"", code, db_);
}

Statement& Statement::Check(int rc) {
  if (rc != SQLITE_OK && bind_error_ == 0) bind_error_ = rc;
  return *this;
}

Statement& Statement::Bind(int index, int64_t value) {
  return Check(sqlite3_bind_int64(stmt_, index, value));
}
Statement& Statement::Bind(int index, double value) {
  return Check(sqlite3_bind_double(stmt_, index, value));
}
Statement& Statement::Bind(int index, std::string_view text) {
  return Check(
      sqlite3_bind_text64(stmt_, index, text.data(), text.size(), SQLITE_TRANSIENT, SQLITE_UTF8));
}
Statement& Statement::BindBlob(int index, std::span<const uint8_t> bytes) {
  // A null data pointer would bind NULL; an empty blob must stay a (zero-length) blob.
  return Check(bytes.empty() ? sqlite3_bind_zeroblob(stmt_, index, 0)
                             : sqlite3_bind_blob64(stmt_, index, bytes.data(), bytes.size(),
                                                   SQLITE_TRANSIENT));
}
Statement& Statement::BindBlobNoCopy(int index, std::span<const uint8_t> bytes) {
  return Check(bytes.empty()
                   ? sqlite3_bind_zeroblob(stmt_, index, 0)
                   : sqlite3_bind_blob64(stmt_, index, bytes.data(), bytes.size(), SQLITE_STATIC));
}
Statement& Statement::BindNull(int index) { return Check(sqlite3_bind_null(stmt_, index)); }

Result<bool> Statement::Step() {
  if (bind_error_ != 0) return ErrorFor(bind_error_);
  int rc = sqlite3_step(stmt_);
  if (rc == SQLITE_ROW) return true;
  if (rc == SQLITE_DONE) return false;
  return ErrorFor(sqlite3_extended_errcode(db_));
}

Status Statement::Run() {
  Result<bool> row = Step();
  RADFARM_RETURN_IF_ERROR(row);
  if (*row) {
    // Drain the rest (e.g. a PRAGMA that reports its value).
    while (true) {
      Result<bool> more = Step();
      RADFARM_RETURN_IF_ERROR(more);
      if (!*more) break;
    }
  }
  return Ok{};
}

void Statement::Reset() {
  sqlite3_reset(stmt_);
  sqlite3_clear_bindings(stmt_);
  bind_error_ = 0;
}

bool Statement::IsNull(int column) const {
  return sqlite3_column_type(stmt_, column) == SQLITE_NULL;
}
int64_t Statement::Int(int column) const { return sqlite3_column_int64(stmt_, column); }
double Statement::Double(int column) const { return sqlite3_column_double(stmt_, column); }
std::string Statement::Text(int column) const {
  const unsigned char* text = sqlite3_column_text(stmt_, column);
  int size = sqlite3_column_bytes(stmt_, column);
  return text != nullptr ? std::string(reinterpret_cast<const char*>(text), size) : std::string();
}
std::vector<uint8_t> Statement::Blob(int column) const {
  const auto* data = static_cast<const uint8_t*>(sqlite3_column_blob(stmt_, column));
  int size = sqlite3_column_bytes(stmt_, column);
  return data != nullptr ? std::vector<uint8_t>(data, data + size) : std::vector<uint8_t>();
}

// --- Transaction -------------------------------------------------------------------------------

Result<Transaction> Transaction::Begin(Database& db) {
  Status begun = db.Exec("BEGIN IMMEDIATE", "begin transaction");
  RADFARM_RETURN_IF_ERROR(begun);
  return Transaction(&db);
}

Transaction::~Transaction() {
  // After SQLITE_FULL, SQLITE_IOERR or SQLITE_NOMEM SQLite may have rolled back already.
  if (db_ != nullptr && db_->InTransaction()) {
    sqlite3_exec(db_->handle(), "ROLLBACK", nullptr, nullptr, nullptr);
  }
}

Transaction::Transaction(Transaction&& other) noexcept : db_(std::exchange(other.db_, nullptr)) {}

Status Transaction::Commit() {
  Database* db = std::exchange(db_, nullptr);
  if (db == nullptr) return Error{"job store: commit of a finished transaction"};
  if (!db->InTransaction()) {
    return Error{"job store " + db->path() +
                 ": commit: the transaction was already rolled back after an earlier error"};
  }
  Status committed = db->Exec("COMMIT", "commit");
  if (!committed.ok() && db->InTransaction()) {
    // A failed COMMIT (e.g. SQLITE_FULL while writing the WAL) leaves the transaction open.
    sqlite3_exec(db->handle(), "ROLLBACK", nullptr, nullptr, nullptr);
  }
  return committed;
}

}  // namespace radfarm::store
