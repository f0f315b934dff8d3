// RAII owners of SQLite objects: Database (a connection), Statement (a prepared statement) and
// Transaction (BEGIN IMMEDIATE ... COMMIT, rolled back unless committed). Every failure returns a
// store error built by sqlite_error.h; nothing throws.
//
// Ownership: each object has one owner; copies are deleted, moves transfer ownership. Statements
// and Transactions borrow their Database's connection, which must outlive them (moving the
// Database is fine: they hold the sqlite3*, not the Database).
//
// Threads: a Database and everything made from it is used by one thread at a time (the connection
// is opened with SQLITE_OPEN_NOMUTEX). The job store keeps all of them on its store thread.
//
// Values only ever reach SQL through bound parameters (Statement::Bind*). Exec() is for fixed SQL
// text written in this library (schema, pragmas), never for text built from values.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "base/result.h"

struct sqlite3;
struct sqlite3_stmt;

namespace radfarm::store {

struct DatabaseOptions {
  bool create = true;          // create the file if missing
  int busy_timeout_ms = 5000;  // wait this long for another connection's lock, then SQLITE_BUSY
  std::string vfs;             // SQLite VFS name; empty: the default (tests inject faults here)
};

class Statement;

class Database {
 public:
  static Result<Database> Open(const std::string& path, const DatabaseOptions& options);
  ~Database();
  Database(Database&& other) noexcept;
  Database& operator=(Database&& other) noexcept;
  Database(const Database&) = delete;
  Database& operator=(const Database&) = delete;

  // Runs fixed SQL text (one or more statements, no parameters). `what` names the step in errors.
  Status Exec(std::string_view sql, std::string_view what);
  Result<Statement> Prepare(std::string_view sql);
  // Runs a statement that returns one integer (e.g. "PRAGMA user_version").
  Result<int64_t> QueryInt(std::string_view sql);
  Result<std::string> QueryText(std::string_view sql);

  // The store error for `code` met while doing `what` on this connection.
  Error ErrorFor(std::string_view what, int code) const;
  int64_t Changes() const;
  int64_t LastInsertRowid() const;
  bool InTransaction() const;
  const std::string& path() const { return path_; }
  sqlite3* handle() const { return db_; }

 private:
  Database(sqlite3* db, std::string path) : db_(db), path_(std::move(path)) {}
  sqlite3* db_ = nullptr;
  std::string path_;
};

// A prepared statement. Bind errors are remembered and returned by the next Step()/Run(), so a
// caller binds several values and checks once.
class Statement {
 public:
  ~Statement();
  Statement(Statement&& other) noexcept;
  Statement& operator=(Statement&& other) noexcept;
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;

  // Parameters are numbered from 1, as in SQLite ("?1").
  Statement& Bind(int index, int64_t value);
  Statement& Bind(int index, double value);
  Statement& Bind(int index, std::string_view text);
  Statement& BindBlob(int index, std::span<const uint8_t> bytes);
  // Without SQLite's copy: `bytes` must stay alive and unchanged until the statement has run.
  Statement& BindBlobNoCopy(int index, std::span<const uint8_t> bytes);
  Statement& BindNull(int index);

  // true: a row is ready to read; false: the statement is done.
  Result<bool> Step();
  // Steps to completion; an error if it fails.
  Status Run();
  // Resets to run again and clears bindings.
  void Reset();

  // Columns are numbered from 0.
  bool IsNull(int column) const;
  int64_t Int(int column) const;
  double Double(int column) const;
  std::string Text(int column) const;
  std::vector<uint8_t> Blob(int column) const;

 private:
  friend class Database;
  Statement(sqlite3* db, sqlite3_stmt* stmt) : db_(db), stmt_(stmt) {}
  Statement& Check(int rc);
  Error ErrorFor(int code) const;

  sqlite3* db_ = nullptr;
  sqlite3_stmt* stmt_ = nullptr;
  int bind_error_ = 0;  // first failing sqlite3_bind_* code, reported by Step()
};

// BEGIN IMMEDIATE: takes the write lock at once, so a busy database fails here (after the busy
// timeout) rather than halfway through. Commit() ends it; otherwise the destructor rolls back.
// If SQLite already rolled back by itself (after SQLITE_FULL or SQLITE_IOERR) nothing is left to
// do.
class Transaction {
 public:
  static Result<Transaction> Begin(Database& db);
  ~Transaction();
  Transaction(Transaction&& other) noexcept;
  Transaction& operator=(Transaction&&) = delete;  // one transaction per object
  Transaction(const Transaction&) = delete;
  Transaction& operator=(const Transaction&) = delete;

  Status Commit();

 private:
  explicit Transaction(Database* db) : db_(db) {}
  Database* db_ = nullptr;  // null once committed or moved from
};

}  // namespace radfarm::store
