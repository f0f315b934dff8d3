// JobRounds: pieces of point work on the agents, of three kinds: a running job's direct-light start
// and its refinement steps' light scores (job_start.cc; patches to agents of protocol version 7,
// elements to version 8) and a finished job's display (job_display.cc; its points, to agents of
// version 6); a scene with a sky's, to version 8 alone. All are cut and leased by DisplayPieces
// and answered by PointResults checked against the piece they answer. A start comes first: a job
// waits on it, where a display only ends a job.
#include <algorithm>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "daemon/jobs/job_rounds.h"

namespace radfarm::daemon {
namespace {

// New leases of `pieces` for `agent` while it holds fewer than `room`.
void LeasePieces(store::JobId id, DisplayPieces& pieces, const PointWork& work,
                 const protocol::SceneHash& context, uint64_t agent, uint32_t room,
                 scheduler::TimePoint now, std::vector<protocol::PointLeaseMsg>* leases) {
  while (pieces.HeldBy(agent) < room) {
    const std::optional<PieceLease> piece = pieces.Next(agent, now);
    if (!piece) break;
    leases->push_back(
        MakePointLease(id, *piece, work, context, static_cast<uint32_t>(kPieceLeaseTime.count())));
  }
}

}  // namespace

std::vector<protocol::PointLeaseMsg> JobRounds::PointLeasesFor(
    uint64_t agent, uint16_t version, uint32_t room,
    const std::function<bool(store::JobId)>& refused) {
  std::vector<protocol::PointLeaseMsg> leases;
  const scheduler::TimePoint now = clock_.Now();
  for (auto& [id, run] : start_runs_) {
    if (version < run.request.version || refused(id)) continue;
    LeasePieces(id, run.pieces, run.request.work, run.request.context->hash, agent, room, now,
                &leases);
  }
  if (version < protocol::kPointLeaseVersion) return leases;
  for (auto& [id, run] : display_runs_) {
    if (!run.pieces || refused(id)) continue;
    if (run.draft->sky() && version < protocol::kSkyVersion) continue;
    LeasePieces(id, *run.pieces, *run.draft->work(), run.draft->context()->hash, agent, room, now,
                &leases);
  }
  return leases;
}

Result<bool> JobRounds::OnPointResult(uint64_t agent, const protocol::PointResultMsg& result) {
  const store::JobId id = static_cast<store::JobId>(result.lease.job_id);
  if (const auto start = start_runs_.find(id);
      start != start_runs_.end() && start->second.pieces.PointsOf(result.lease.batch_id)) {
    return OnStartResult(agent, start->second, result);
  }
  const auto it = display_runs_.find(id);
  if (it == display_runs_.end() || !it->second.pieces) return false;  // late: dropped
  DisplayRun& run = it->second;
  const std::optional<std::pair<size_t, size_t>> points =
      run.pieces->PointsOf(result.lease.batch_id);
  if (!points) return false;  // of an earlier step, or of a start that ended
  Result<PointValues> values =
      ValuesOfResult(result, *run.draft->work(), points->first, points->second);
  if (!values) {
    run.pieces->OnAgentLost(agent);
    return Error{"job " + std::to_string(id) + ": " + values.error()};
  }
  const bool accepted =
      run.pieces->OnResult(agent, result.lease.batch_id, result.lease.attempt_id,
                           std::move(*values)) == DisplayPieces::Verdict::kAccepted;
  if (accepted) {
    AddToTimeline(&run.timeline, JobPhase::kDisplay, kRanOnAgents, 0, result.compute_seconds);
  }
  if (run.pieces->Complete()) {
    PointValues whole = run.pieces->TakeValues();
    run.pieces.reset();
    ApplyDisplayStep(id, run.serial, std::move(whole));
  }
  return accepted;
}

void JobRounds::OnPointAgentLost(uint64_t agent) {
  for (auto& [id, run] : start_runs_) run.pieces.OnAgentLost(agent);
  for (auto& [id, run] : display_runs_) {
    if (run.pieces) run.pieces->OnAgentLost(agent);
  }
}

size_t JobRounds::ReturnPointPieces(uint64_t agent, const protocol::LeaseRef& lease) {
  const store::JobId id = static_cast<store::JobId>(lease.job_id);
  DisplayPieces* pieces = nullptr;
  if (const auto start = start_runs_.find(id);
      start != start_runs_.end() && start->second.pieces.PointsOf(lease.batch_id)) {
    pieces = &start->second.pieces;
  } else if (const auto display = display_runs_.find(id);
             display != display_runs_.end() && display->second.pieces) {
    pieces = &*display->second.pieces;
  }
  if (pieces == nullptr) return 0;
  const uint32_t before = pieces->HeldBy(agent);
  pieces->Return(agent, lease.batch_id, lease.attempt_id);
  return before - pieces->HeldBy(agent);
}

std::shared_ptr<const protocol::PackedScene> JobRounds::PointContextOf(
    const protocol::SceneHash& hash) const {
  for (const auto& [id, run] : start_runs_) {
    if (run.request.context->hash == hash) return run.request.context;
  }
  for (const auto& [id, run] : display_runs_) {
    if (run.pieces && run.draft->context() && run.draft->context()->hash == hash) {
      return run.draft->context();
    }
  }
  return nullptr;
}

bool JobRounds::LeasingPoints() const {
  return !start_runs_.empty() ||
         std::any_of(display_runs_.begin(), display_runs_.end(),
                     [](const auto& run) { return run.second.pieces.has_value(); });
}

}  // namespace radfarm::daemon
