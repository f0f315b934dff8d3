// JobRounds: a running job's direct-light start and its refinement steps' light scores on the
// agents. The compute thread building the job's solver or refining its mesh (RunningJob::Prepare,
// or Reduce) hands the work over (start_source.h, start_handoff.h) and waits; here its patches or
// elements are cut into pieces and leased to agents of protocol version 7 (a start) or 8 (scores)
// (job_point_leases.cc), and the values of every piece, in order, go back. Where no such agent is
// there, or the work is small, the compute thread is told to trace it itself. A job dropped
// meanwhile (cancelled, paused) or a master stopping ends the wait with an error.
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

LightScoreSource JobRounds::ScoreSourceFor(store::JobId id) const {
  return AgentsLightScoreSource(start_handoff_, id);
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
    const size_t agents = agents_.piece_agents ? agents_.piece_agents(request.version) : 0;
    const size_t patches = request.work.size();
    if (agents == 0 || patches < kLocalPiecesWork) {
      start_handoff_->Answer(ticket, std::optional<PointValues>());
      continue;
    }
    const uint32_t step = kStartStepBit | (++start_serial_ & ~kStartStepBit);
    StartRun run{ticket, std::move(request),
                 DisplayPieces(step, patches, PiecePoints(patches, agents), kPieceLeaseTime)};
    LogLine(LogLevel::kInfo, "job " + std::to_string(id))
        << (run.request.work.scores() ? "refinement's light scores: " : "direct-light start: ")
        << patches << (run.request.work.scores() ? " elements in " : " patches in ")
        << run.pieces.pieces() << " pieces for " << agents << " agents";
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
    PieceSeconds& seconds = start_agent_seconds_[id];
    (run.request.work.scores() ? seconds.scores : seconds.start) += run.agent_seconds;
    start_handoff_->Answer(run.ticket, std::optional<PointValues>(run.pieces.TakeValues()));
    start_runs_.erase(id);  // `run` goes with it
  }
  return accepted;
}

void JobRounds::TakeBackOrphanedStarts() {
  for (auto it = start_runs_.begin(); it != start_runs_.end();) {
    const auto& [id, run] = *it;
    if (agents_.piece_agents && agents_.piece_agents(run.request.version) > 0) {
      ++it;
      continue;
    }
    LogLine(LogLevel::kWarning, "job " + std::to_string(id))
        << "no agent left for its "
        << (run.request.work.scores() ? "refinement's light scores" : "direct-light start") << " ("
        << run.pieces.done() << " of " << run.pieces.pieces() << " pieces in): traced here";
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

void JobRounds::AddStartSeconds(RunningJob& runner, JobPhase scores_phase) {
  const auto it = start_agent_seconds_.find(runner.id());
  if (it == start_agent_seconds_.end()) return;
  if (it->second.start > 0) runner.AddPieceAgentSeconds(JobPhase::kDirectLight, it->second.start);
  if (it->second.scores > 0) runner.AddPieceAgentSeconds(scores_phase, it->second.scores);
  start_agent_seconds_.erase(it);
}

}  // namespace radfarm::daemon
