#include "tests/farm/kept_results.h"

#include "store/database.h"

namespace radfarm::testing {

int64_t KeptResults(const std::string& db_path, int64_t job) {
  Result<store::Database> db = store::Database::Open(db_path, {});
  if (!db) return -1;
  Result<store::Statement> read =
      db->Prepare("SELECT count(*) FROM round_results WHERE job_id = ?1");
  if (!read) return -1;
  read->Bind(1, job);
  Result<bool> row = read->Step();
  return row && *row ? read->Int(0) : -1;
}

KeptRound NewestKeptRound(const std::string& db_path, int64_t job) {
  Result<store::Database> db = store::Database::Open(db_path, {});
  if (!db) return {};
  Result<store::Statement> read = db->Prepare(
      "SELECT round, count(*) FROM round_results WHERE job_id = ?1 GROUP BY round"
      " ORDER BY round DESC LIMIT 1");
  if (!read) return {};
  read->Bind(1, job);
  Result<bool> row = read->Step();
  if (!row || !*row) return {};
  return {read->Int(0), read->Int(1)};
}

}  // namespace radfarm::testing
