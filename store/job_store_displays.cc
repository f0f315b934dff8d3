// JobStore: finished jobs' displays (displays, schema version 9).
#include <utility>

#include "base/result.h"
#include "store/blob_checksum.h"
#include "store/job_store.h"

namespace radfarm::store {

Status JobStore::PutDisplay(JobId job, uint32_t round, std::span<const uint8_t> display) {
  const Checksum checksum = BlobChecksum(display);
  Result<Statement> stmt = db_.Prepare(
      "INSERT OR REPLACE INTO displays (job_id, round, display, checksum) VALUES (?1, ?2, ?3, ?4)");
  RADFARM_RETURN_IF_ERROR(stmt);
  stmt->Bind(1, job).Bind(2, int64_t{round}).BindBlob(3, display).BindBlob(4, checksum);
  return stmt->Run();
}

Result<std::optional<StoredDisplay>> JobStore::GetDisplay(JobId job) {
  Result<Statement> stmt =
      db_.Prepare("SELECT round, display, checksum FROM displays WHERE job_id = ?1");
  RADFARM_RETURN_IF_ERROR(stmt);
  stmt->Bind(1, job);
  Result<bool> row = stmt->Step();
  RADFARM_RETURN_IF_ERROR(row);
  if (!*row) return std::optional<StoredDisplay>();
  StoredDisplay stored;
  stored.round = static_cast<uint32_t>(stmt->Int(0));
  stored.display = stmt->Blob(1);
  if (!ChecksumMatches(stmt->Blob(2), BlobChecksum(stored.display))) {
    return Error{"job store " + path() + ": the display of job " + std::to_string(job) +
                 " is damaged (its bytes do not match its checksum)"};
  }
  return std::optional<StoredDisplay>(std::move(stored));
}

}  // namespace radfarm::store
