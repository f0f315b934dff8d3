// JobRounds: a running job's direct-light start on the agents. The compute thread building the
// job's solver (RunningJob::Prepare, or Reduce at a refinement restart) hands the start over
// (start_source.h, start_handoff.h) and waits; here its patches are cut into pieces and leased to
// agents of protocol version 7, or 8 for a scene with a sky (job_point_leases.cc), and the values
// of every piece, in patch order, go back. Where no such agent is there, or the start is small, the
// compute thread is told to trace it itself. A job dropped meanwhile (cancelled, paused) or a
// master stopping ends the wait with an error.
#include <string>
#include <utility>

#include "daemon/jobs/job_rounds.h"
#include "daemon/jobs/start_source.h"
#include "loop/log.h"

namespace radfarm::daemon {

using loop::LogLevel;
using loop::LogLine;

StartLightSource JobRounds::StartSourceFor(store::JobId id) const {
  return AgentsStartSource(start_handoff_, id);
}

void JobRounds::TakeStartRequests() {
  bool leased = false;
  for (auto& [ticket, request] : start_handoff_->Take()) {
    const store::JobId id = request.job;
    const auto starting = starting_.find(id);
    const bool dropped = starting != starting_.end() ? starting->second : !runners_.count(id);
    if (stopping_ || dropped) {
      start_handoff_->Answer(ticket, Error{"job " + std::to_string(id) + " was dropped"});
      continue;
    }
    const size_t agents = StartAgents(request.sky);
    const size_t patches = request.work.size();
    if (agents == 0 || patches < kLocalPiecesWork) {
      start_handoff_->Answer(ticket, std::optional<PointValues>());
      continue;
    }
    const uint32_t step = kStartStepBit | (++start_serial_ & ~kStartStepBit);
    StartRun run{ticket, std::move(request),
                 DisplayPieces(step, patches, PiecePoints(patches, agents), kPieceLeaseTime)};
    LogLine(LogLevel::kInfo, "job " + std::to_string(id))
        << "direct-light start: " << patches << " patches in " << run.pieces.pieces()
        << " pieces for " << agents << " agents";
    DropStart(id);  // a job waits on one start at a time: none is left, but be sure
    start_runs_.emplace(id, std::move(run));
    leased = true;
  }
  if (leased) agents_.dispatch_all();
}

Result<bool> JobRounds::OnStartResult(uint64_t agent, StartRun& run,
                                      const protocol::PointResultMsg& result) {
  const store::JobId id = run.request.job;
  const std::optional<std::pair<size_t, size_t>> patches =
      run.pieces.PointsOf(result.lease.batch_id);
  Result<PointValues> values =
      ValuesOfResult(result, run.request.work, patches->first, patches->second);
  if (!values) {
    run.pieces.OnAgentLost(agent);
    return Error{"job " + std::to_string(id) + ": its start: " + values.error()};
  }
  const bool accepted =
      run.pieces.OnResult(agent, result.lease.batch_id, result.lease.attempt_id,
                          std::move(*values)) == DisplayPieces::Verdict::kAccepted;
  if (accepted) run.agent_seconds += result.compute_seconds;
  if (run.pieces.Complete()) {
    start_agent_seconds_[id] += run.agent_seconds;
    start_handoff_->Answer(run.ticket, std::optional<PointValues>(run.pieces.TakeValues()));
    start_runs_.erase(id);  // `run` goes with it
  }
  return accepted;
}

size_t JobRounds::StartAgents(bool sky) const {
  const std::function<size_t()>& count = sky ? agents_.sky_agents : agents_.start_agents;
  return count ? count() : 0;
}

void JobRounds::TakeBackOrphanedStarts() {
  for (auto it = start_runs_.begin(); it != start_runs_.end();) {
    auto& [id, run] = *it;
    if (StartAgents(run.request.sky) > 0) {
      ++it;
      continue;
    }
    LogLine(LogLevel::kWarning, "job " + std::to_string(id))
        << "no agent left for its direct-light start (" << run.pieces.done() << " of "
        << run.pieces.pieces() << " pieces in): traced here";
    start_handoff_->Answer(run.ticket, std::optional<PointValues>());
    it = start_runs_.erase(it);
  }
}

void JobRounds::DropStart(store::JobId id) {
  const auto it = start_runs_.find(id);
  if (it == start_runs_.end()) return;
  start_handoff_->Answer(it->second.ticket, Error{"job " + std::to_string(id) + " was dropped"});
  start_runs_.erase(it);
  agents_.cancel_job(id);  // agents drop its pieces; results still in flight are ignored
}

void JobRounds::AddStartSeconds(RunningJob& runner) {
  const auto it = start_agent_seconds_.find(runner.id());
  if (it == start_agent_seconds_.end()) return;
  runner.AddStartAgentSeconds(it->second);
  start_agent_seconds_.erase(it);
}

}  // namespace radfarm::daemon
