// JobStore: the accepted batch results of a round in progress (round_results, schema version 6).
#include <utility>

#include "base/result.h"
#include "store/batch_result_codec.h"
#include "store/blob_checksum.h"
#include "store/job_store.h"

namespace radfarm::store {
namespace {

// The batch_rays column holds the taper too, in its high 32 bits: rows written before the taper
// read as untapered, and the schema is unchanged.
int64_t SizingColumn(const StoredBatchResult& r) {
  return static_cast<int64_t>(uint64_t{r.taper_ways} << 32 | r.batch_rays);
}

Checksum ChecksumOf(JobId job, const StoredBatchResult& r, std::span<const uint8_t> blob) {
  return RoundResultChecksum({job, int64_t{r.batch.round}, int64_t{r.index},
                              int64_t{r.batch.shooter}, static_cast<int64_t>(r.batch.first_ray),
                              int64_t{r.batch.ray_count}, SizingColumn(r), blob});
}

}  // namespace

Status JobStore::SaveRoundResults(JobId job, std::span<const StoredBatchResult> results) {
  // Encode and checksum before taking the write lock.
  std::vector<std::vector<uint8_t>> blobs;
  std::vector<Checksum> checksums;
  blobs.reserve(results.size());
  checksums.reserve(results.size());
  for (const StoredBatchResult& r : results) {
    blobs.push_back(EncodeBatchResult(r.result));
    checksums.push_back(ChecksumOf(job, r, blobs.back()));
  }
  Result<Transaction> transaction = Transaction::Begin(db_);
  RADFARM_RETURN_IF_ERROR(transaction);
  Result<Statement> stmt = db_.Prepare(
      "INSERT OR REPLACE INTO round_results (job_id, round, batch, shooter, first_ray, ray_count,"
      " batch_rays, result, checksum) VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9)");
  RADFARM_RETURN_IF_ERROR(stmt);
  for (size_t k = 0; k < results.size(); ++k) {
    const StoredBatchResult& r = results[k];
    stmt->Bind(1, job)
        .Bind(2, int64_t{r.batch.round})
        .Bind(3, int64_t{r.index})
        .Bind(4, int64_t{r.batch.shooter})
        .Bind(5, static_cast<int64_t>(r.batch.first_ray))
        .Bind(6, int64_t{r.batch.ray_count})
        .Bind(7, SizingColumn(r))
        .BindBlob(8, blobs[k])
        .BindBlob(9, checksums[k]);
    RADFARM_RETURN_IF_ERROR(stmt->Run());
    stmt->Reset();
  }
  return transaction->Commit();
}

Result<StoredRoundResults> JobStore::LoadRoundResults(JobId job,
                                                      std::optional<uint32_t> after_round) {
  Result<Statement> stmt = db_.Prepare(
      "SELECT round, batch, shooter, first_ray, ray_count, batch_rays, result, checksum"
      " FROM round_results WHERE job_id = ?1 AND round > ?2 ORDER BY round, batch");
  RADFARM_RETURN_IF_ERROR(stmt);
  stmt->Bind(1, job).Bind(2, after_round ? int64_t{*after_round} : int64_t{-1});
  StoredRoundResults out;
  std::vector<std::pair<int64_t, int64_t>> bad;  // (round, batch)
  while (true) {
    Result<bool> row = stmt->Step();
    RADFARM_RETURN_IF_ERROR(row);
    if (!*row) break;
    StoredBatchResult r;
    r.batch.round = static_cast<uint32_t>(stmt->Int(0));
    r.index = static_cast<uint32_t>(stmt->Int(1));
    r.batch.shooter = static_cast<uint32_t>(stmt->Int(2));
    r.batch.first_ray = static_cast<uint64_t>(stmt->Int(3));
    r.batch.ray_count = static_cast<uint32_t>(stmt->Int(4));
    const auto sizing = static_cast<uint64_t>(stmt->Int(5));
    r.batch_rays = static_cast<uint32_t>(sizing);
    r.taper_ways = static_cast<uint32_t>(sizing >> 32);
    const std::vector<uint8_t> blob = stmt->Blob(6);
    const std::string where = "job store " + path() + ": the stored result of job " +
                              std::to_string(job) + " round " + std::to_string(r.batch.round) +
                              " batch " + std::to_string(r.index);
    Result<BatchResult> result = Error{"its bytes do not match its checksum"};
    if (ChecksumMatches(stmt->Blob(7), ChecksumOf(job, r, blob))) result = DecodeBatchResult(blob);
    if (!result) {
      out.damaged.push_back(where + " is damaged (" + result.error() + "); it is computed again");
      bad.emplace_back(stmt->Int(0), stmt->Int(1));
      continue;
    }
    r.result = std::move(*result);
    out.results.push_back(std::move(r));
  }
  if (bad.empty()) return out;
  Result<Statement> erase =
      db_.Prepare("DELETE FROM round_results WHERE job_id = ?1 AND round = ?2 AND batch = ?3");
  RADFARM_RETURN_IF_ERROR(erase);
  for (const auto& [round, batch] : bad) {
    erase->Bind(1, job).Bind(2, round).Bind(3, batch);
    RADFARM_RETURN_IF_ERROR(erase->Run());
    erase->Reset();
  }
  return out;
}

Result<int64_t> JobStore::CountRoundResults(JobId job, uint32_t round) {
  Result<Statement> stmt =
      db_.Prepare("SELECT count(*) FROM round_results WHERE job_id = ?1 AND round = ?2");
  RADFARM_RETURN_IF_ERROR(stmt);
  stmt->Bind(1, job).Bind(2, int64_t{round});
  Result<bool> row = stmt->Step();
  RADFARM_RETURN_IF_ERROR(row);
  return stmt->Int(0);
}

Status JobStore::RewindJob(JobId job, uint32_t from_round, std::span<const uint32_t> discard,
                           bool discard_all) {
  Result<Transaction> transaction = Transaction::Begin(db_);
  RADFARM_RETURN_IF_ERROR(transaction);
  const int64_t round = from_round;
  for (const char* sql : {"DELETE FROM checkpoints WHERE job_id = ?1 AND round >= ?2",
                          "DELETE FROM round_results WHERE job_id = ?1 AND round > ?2"}) {
    Result<Statement> stmt = db_.Prepare(sql);
    RADFARM_RETURN_IF_ERROR(stmt);
    stmt->Bind(1, job).Bind(2, round);
    RADFARM_RETURN_IF_ERROR(stmt->Run());
  }
  Result<Statement> erase = db_.Prepare(
      discard_all ? "DELETE FROM round_results WHERE job_id = ?1 AND round = ?2"
                  : "DELETE FROM round_results WHERE job_id = ?1 AND round = ?2 AND batch = ?3");
  RADFARM_RETURN_IF_ERROR(erase);
  if (discard_all) {
    erase->Bind(1, job).Bind(2, round);
    RADFARM_RETURN_IF_ERROR(erase->Run());
  }
  for (size_t k = 0; !discard_all && k < discard.size(); ++k) {
    erase->Bind(1, job).Bind(2, round).Bind(3, int64_t{discard[k]});
    RADFARM_RETURN_IF_ERROR(erase->Run());
    erase->Reset();
  }
  return transaction->Commit();
}

Status JobStore::PruneRoundResults(JobId job, uint32_t up_to_round) {
  Result<Statement> stmt =
      db_.Prepare("DELETE FROM round_results WHERE job_id = ?1 AND round <= ?2");
  RADFARM_RETURN_IF_ERROR(stmt);
  stmt->Bind(1, job).Bind(2, int64_t{up_to_round});
  return stmt->Run();
}

Status JobStore::PruneEndedJobsRoundResults() {
  return db_.Exec(
      "DELETE FROM round_results WHERE job_id IN "
      "(SELECT id FROM jobs WHERE state IN ('done', 'failed', 'cancelled'))",
      "delete the kept results of ended jobs");
}

}  // namespace radfarm::store
