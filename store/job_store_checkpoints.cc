// JobStore: rounds and checkpoints (the rest is in job_store.cc).
#include <chrono>
#include <utility>

#include "base/result.h"
#include "store/blob_checksum.h"
#include "store/blob_codec.h"
#include "store/job_store.h"

namespace radfarm::store {
namespace {

using Clock = std::chrono::steady_clock;

double Seconds(Clock::duration d) { return std::chrono::duration<double>(d).count(); }

}  // namespace

Status JobStore::InsertRound(const RoundRecord& round, int64_t now) {
  Result<Statement> stmt = db_.Prepare(
      "INSERT INTO rounds (job_id, round, shooters, rays, unshot_fraction, unshot_power,"
      " duration_seconds, recorded_at_ms, escaped_rays, back_rays)"
      " VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10)"
      " ON CONFLICT (job_id, round) DO UPDATE SET shooters = excluded.shooters,"
      " rays = excluded.rays, unshot_fraction = excluded.unshot_fraction,"
      " unshot_power = excluded.unshot_power, duration_seconds = excluded.duration_seconds,"
      " recorded_at_ms = excluded.recorded_at_ms, escaped_rays = excluded.escaped_rays,"
      " back_rays = excluded.back_rays");
  RADFARM_RETURN_IF_ERROR(stmt);
  stmt->Bind(1, round.job)
      .Bind(2, int64_t{round.round})
      .Bind(3, int64_t{round.shooters})
      .Bind(4, static_cast<int64_t>(round.rays))
      .Bind(5, round.unshot_fraction)
      .Bind(6, round.unshot_power)
      .Bind(7, round.duration_seconds)
      .Bind(8, now)
      .Bind(9, static_cast<int64_t>(round.escaped_rays))
      .Bind(10, static_cast<int64_t>(round.back_rays));
  return stmt->Run();
}

Status JobStore::RecordRound(const RoundRecord& round) { return InsertRound(round, now_ms_()); }

Result<std::vector<RoundRecord>> JobStore::ListRounds(JobId job) {
  Result<Statement> stmt = db_.Prepare(
      "SELECT job_id, round, shooters, rays, unshot_fraction, unshot_power, duration_seconds,"
      " escaped_rays, back_rays"
      " FROM rounds WHERE job_id = ?1 ORDER BY round");
  RADFARM_RETURN_IF_ERROR(stmt);
  stmt->Bind(1, job);
  std::vector<RoundRecord> rounds;
  while (true) {
    Result<bool> row = stmt->Step();
    RADFARM_RETURN_IF_ERROR(row);
    if (!*row) return rounds;
    rounds.push_back({stmt->Int(0), static_cast<uint32_t>(stmt->Int(1)),
                      static_cast<uint32_t>(stmt->Int(2)), static_cast<uint64_t>(stmt->Int(3)),
                      stmt->Double(4), stmt->Double(5), stmt->Double(6),
                      static_cast<uint64_t>(stmt->Int(7)), static_cast<uint64_t>(stmt->Int(8))});
  }
}

Status JobStore::SaveCheckpoint(const RoundRecord& round, const Checkpoint& checkpoint,
                                CheckpointCost* cost) {
  if (checkpoint.job != round.job || checkpoint.round != round.round) {
    return Error{"job store: checkpoint of job " + std::to_string(checkpoint.job) + " round " +
                 std::to_string(checkpoint.round) + " saved with the row of job " +
                 std::to_string(round.job) + " round " + std::to_string(round.round)};
  }
  if (checkpoint.radiosity.size() != checkpoint.unshot.size()) {
    return Error{"job store: checkpoint of job " + std::to_string(checkpoint.job) + ": " +
                 std::to_string(checkpoint.radiosity.size()) + " radiosity values but " +
                 std::to_string(checkpoint.unshot.size()) + " unshot values"};
  }
  // Encode before taking the write lock: the transaction holds it only for the writes.
  const auto encode_start = Clock::now();
  // Views of the values themselves on little-endian hosts: 48 MB not copied at 10^6 patches.
  std::vector<uint8_t> radiosity_buffer, unshot_buffer;
  const std::span<const uint8_t> radiosity = RgbBlob(checkpoint.radiosity, &radiosity_buffer);
  const std::span<const uint8_t> unshot = RgbBlob(checkpoint.unshot, &unshot_buffer);
  std::vector<uint8_t> energy = EncodeEnergy(checkpoint.energy);
  const Checksum checksum = CheckpointChecksum(
      {checkpoint.job, int64_t{checkpoint.round}, int64_t{checkpoint.rounds_done},
       int64_t{checkpoint.refine_points}, radiosity, unshot, energy, &checkpoint.scene_hash,
       &checkpoint.stop_reason});
  int64_t now = now_ms_();
  const auto commit_start = Clock::now();

  Result<Transaction> transaction = Transaction::Begin(db_);
  RADFARM_RETURN_IF_ERROR(transaction);
  RADFARM_RETURN_IF_ERROR(InsertRound(round, now));
  // The rows kept for a restart of this round and those before stay: a restart reads only rounds
  // after its checkpoint, and PruneRoundResults deletes them in a transaction of their own (on a
  // big scene, deleting several rounds' rows took most of a checkpoint's commit).
  Result<Statement> stmt = db_.Prepare(
      "INSERT OR REPLACE INTO checkpoints (job_id, round, rounds_done, patches, radiosity, unshot,"
      " energy, created_at_ms, scene_hash, refine_points, stop_reason, checksum)"
      " VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10, ?11, ?12)");
  RADFARM_RETURN_IF_ERROR(stmt);
  stmt->Bind(1, checkpoint.job)
      .Bind(2, int64_t{checkpoint.round})
      .Bind(3, int64_t{checkpoint.rounds_done})
      .Bind(4, static_cast<int64_t>(checkpoint.radiosity.size()))
      .BindBlobNoCopy(5, radiosity)  // both outlive stmt->Run() below
      .BindBlobNoCopy(6, unshot)
      .BindBlob(7, energy)
      .Bind(8, now)
      .Bind(10, int64_t{checkpoint.refine_points})
      .BindBlob(12, checksum);
  for (const auto& [index, text] :
       {std::pair(9, &checkpoint.scene_hash), std::pair(11, &checkpoint.stop_reason)}) {
    if (*text) {
      stmt->Bind(index, **text);
    } else {
      stmt->BindNull(index);
    }
  }
  RADFARM_RETURN_IF_ERROR(stmt->Run());
  RADFARM_RETURN_IF_ERROR(transaction->Commit());
  if (cost != nullptr) {
    cost->bytes = radiosity.size() + unshot.size() + energy.size() + checksum.size();
    cost->encode_seconds = Seconds(commit_start - encode_start);
    cost->commit_seconds = Seconds(Clock::now() - commit_start);
  }
  return Ok{};
}

Result<std::optional<Checkpoint>> JobStore::LoadLatestCheckpoint(
    JobId job, std::vector<DamagedCheckpoint>* damaged) {
  Result<Statement> stmt = db_.Prepare(
      "SELECT round, rounds_done, radiosity, unshot, energy, created_at_ms, scene_hash,"
      " refine_points, stop_reason, checksum FROM checkpoints"
      " WHERE job_id = ?1 ORDER BY round DESC");
  RADFARM_RETURN_IF_ERROR(stmt);
  stmt->Bind(1, job);
  // Newest first; one whose bytes do not match its checksum is passed over for the one before.
  while (true) {
    Result<bool> row = stmt->Step();
    RADFARM_RETURN_IF_ERROR(row);
    if (!*row) return std::optional<Checkpoint>();
    Checkpoint checkpoint;
    checkpoint.job = job;
    checkpoint.round = static_cast<uint32_t>(stmt->Int(0));
    checkpoint.rounds_done = static_cast<uint32_t>(stmt->Int(1));
    const std::vector<uint8_t> radiosity_blob = stmt->Blob(2), unshot_blob = stmt->Blob(3),
                               energy_blob = stmt->Blob(4);
    checkpoint.created_at_ms = stmt->Int(5);
    if (!stmt->IsNull(6)) checkpoint.scene_hash = stmt->Text(6);
    checkpoint.refine_points = static_cast<uint32_t>(stmt->Int(7));
    if (!stmt->IsNull(8)) checkpoint.stop_reason = stmt->Text(8);
    const Checksum computed =
        CheckpointChecksum({job, int64_t{checkpoint.round}, int64_t{checkpoint.rounds_done},
                            int64_t{checkpoint.refine_points}, radiosity_blob, unshot_blob,
                            energy_blob, &checkpoint.scene_hash, &checkpoint.stop_reason});
    if (!ChecksumMatches(stmt->Blob(9), computed)) {
      const std::string why = "job store " + path() + ": the checkpoint of job " +
                              std::to_string(job) + " round " + std::to_string(checkpoint.round) +
                              " is damaged (its bytes do not match its checksum)";
      if (damaged == nullptr) return Error{why};
      damaged->push_back({checkpoint.round, why});
      continue;
    }
    Result<std::vector<Rgb>> radiosity = DecodeRgbs(radiosity_blob);
    RADFARM_RETURN_IF_ERROR(radiosity);
    Result<std::vector<Rgb>> unshot = DecodeRgbs(unshot_blob);
    RADFARM_RETURN_IF_ERROR(unshot);
    Result<EnergyAccount> energy = DecodeEnergy(energy_blob);
    RADFARM_RETURN_IF_ERROR(energy);
    checkpoint.radiosity = std::move(*radiosity);
    checkpoint.unshot = std::move(*unshot);
    checkpoint.energy = *energy;
    return std::optional<Checkpoint>(std::move(checkpoint));
  }
}

Status JobStore::DeleteCheckpoint(JobId job, uint32_t round) {
  Result<Statement> stmt = db_.Prepare("DELETE FROM checkpoints WHERE job_id = ?1 AND round = ?2");
  RADFARM_RETURN_IF_ERROR(stmt);
  stmt->Bind(1, job).Bind(2, int64_t{round});
  return stmt->Run();
}

Result<std::optional<std::string>> JobStore::LoadLatestStopReason(JobId job) {
  Result<Statement> stmt = db_.Prepare(
      "SELECT stop_reason FROM checkpoints WHERE job_id = ?1 ORDER BY round DESC LIMIT 1");
  RADFARM_RETURN_IF_ERROR(stmt);
  stmt->Bind(1, job);
  Result<bool> row = stmt->Step();
  RADFARM_RETURN_IF_ERROR(row);
  if (!*row || stmt->IsNull(0)) return std::optional<std::string>();
  return std::optional<std::string>(stmt->Text(0));
}

Status JobStore::PruneCheckpoints(JobId job, int keep_last) {
  if (keep_last < 0) return Error{"job store: PruneCheckpoints keep_last must be >= 0"};
  Result<Statement> stmt = db_.Prepare(
      "DELETE FROM checkpoints WHERE job_id = ?1 AND round NOT IN ("
      "  SELECT round FROM checkpoints WHERE job_id = ?1 ORDER BY round DESC LIMIT ?2)");
  RADFARM_RETURN_IF_ERROR(stmt);
  stmt->Bind(1, job).Bind(2, int64_t{keep_last});
  return stmt->Run();
}

Result<std::optional<std::pair<uint32_t, int64_t>>> JobStore::LatestCheckpointStamp(JobId job) {
  Result<Statement> stmt = db_.Prepare(
      "SELECT round, created_at_ms FROM checkpoints WHERE job_id = ?1 ORDER BY round DESC LIMIT 1");
  RADFARM_RETURN_IF_ERROR(stmt);
  stmt->Bind(1, job);
  Result<bool> row = stmt->Step();
  RADFARM_RETURN_IF_ERROR(row);
  if (!*row) return std::optional<std::pair<uint32_t, int64_t>>();
  return std::optional(std::pair(static_cast<uint32_t>(stmt->Int(0)), stmt->Int(1)));
}

Result<int64_t> JobStore::CountCheckpoints(JobId job) {
  Result<Statement> stmt = db_.Prepare("SELECT count(*) FROM checkpoints WHERE job_id = ?1");
  RADFARM_RETURN_IF_ERROR(stmt);
  stmt->Bind(1, job);
  Result<bool> row = stmt->Step();
  RADFARM_RETURN_IF_ERROR(row);
  return stmt->Int(0);
}

}  // namespace radfarm::store
