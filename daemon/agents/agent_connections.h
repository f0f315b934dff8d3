// AgentConnections: the master's side of its agent connections. It accepts connections (one
// AgentLink each; those still in the handshake under DoorKeeper's quota, door_keeper.h), admits
// up to max_agents authenticated agents and max_connections_per_agent under one name (the rest
// are refused with a Close saying why, right after their handshake), charges every connection's
// unfinished frames to one FrameBudget of max_frame_bytes_held (loop/frame_budget.h), hands
// leases of the running jobs' rounds to agents with room (Dispatch), takes their results, lease
// returns and scene requests, sends heartbeats, and takes the leases of an agent that disconnects
// or misses its heartbeats away (the job's scheduler requeues them).
//
// Agent bookkeeping: an agent that missed its heartbeats is stale (no work until it speaks
// again); one that handed leases back as draining or overloaded declines work on this connection;
// one whose results authenticate but fail validation earns a strike for that job, and after
// JobBlocklist::kStrikes it is blocklisted for that job, by its name, for
// SchedulerOptions::blocklist_duration, and closed with Close(Blocklisted) saying why. A frame that
// fails authentication is the wire's fault: AgentLink closes that connection, nothing more. Every
// connection refused or closed before it
// authenticated is logged, at most kDoorLogLines lines per kDoorLogWindow (LogRateLimiter).
//
// Loop thread only. It reads and drives the jobs' schedulers through JobRounds.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "base/log_rate_limiter.h"
#include "daemon/agents/agent_credentials.h"
#include "daemon/agents/agent_link.h"
#include "daemon/agents/door_keeper.h"
#include "daemon/agents/job_blocklist.h"
#include "daemon/config/master_config.h"
#include "daemon/jobs/clock.h"
#include "daemon/jobs/job_rounds.h"
#include "daemon/jobs/store_thread.h"
#include "loop/event_loop.h"
#include "loop/framed_connection.h"
#include "protocol/farm_secret.h"

namespace radfarm::daemon {

class AgentConnections {
 public:
  AgentConnections(loop::EventLoop& loop, const Clock& clock, const MasterConfig& config,
                   const protocol::FarmSecret& secret, const scheduler::SchedulerOptions& options,
                   StoreThread& store, JobRounds& jobs,
                   const std::vector<store::AgentCredential>& credentials);
  AgentConnections(const AgentConnections&) = delete;
  AgentConnections& operator=(const AgentConnections&) = delete;

  // The listener's callback: a new connection, still to authenticate.
  void OnConnection(std::unique_ptr<loop::FramedConnection> connection);
  // Hands leases to every agent with room.
  void DispatchAll();
  // A result of the agent called `name` failed exact validation (JobRounds::Rewind): it is
  // blocklisted for the job at once, and its connections close saying why.
  void Convict(store::JobId job, const std::string& name, const std::string& why);
  // Tells every agent to drop the batches of job `id`.
  void CancelJob(store::JobId id);
  // Agents that get work when a job starts: authenticated and not stale, by id.
  std::vector<uint64_t> Available() const;
  // The available agents' last reported rays/s (their heartbeats), summed.
  double ReportedRaysPerSecond() const;
  // Available agents of protocol `version` or later: 6 trace the display's points, 7 a start's
  // patches too.
  size_t PointAgents(uint16_t version) const;
  // The heartbeat: marks agents silent past agent_timeout_ms stale (their leases go back),
  // sends the others a heartbeat, then dispatches.
  void Heartbeat();

  // Authenticated agents (what `radfarm agents` lists), by id.
  std::vector<const AgentLink*> Authenticated() const;
  // Authenticated and not stale: the agents working for the farm.
  size_t active() const;
  // The connections at the door: strangers waiting, evicted, refused (control `agents`).
  const DoorCounters& doors() const { return doors_.counters(); }
  uint32_t max_unauthenticated() const { return doors_.max_unauthenticated(); }
  // What the agents' unfinished frames hold now, at most, and are refused (control `agents`).
  const loop::FrameBudget& frame_budget() const { return *frame_budget_; }

  // After the store committed `radfarm agents enroll`: the name proves itself with this key from
  // its next handshake on (a live connection stays). Returns the key to hand out.
  protocol::FarmSecret Enrolled(const store::AgentCredential& credential);
  // Every enrolled name and its state, by name.
  std::vector<store::AgentCredential> Enrollments() const { return credentials_.List(); }
  // After the store committed `radfarm agents revoke`: the name is refused from now on, and its
  // connections (authenticated or still in the handshake) close at once. Returns how many.
  size_t Revoked(const store::AgentCredential& credential);

  // Shutdown: tells every agent and refuses new connections and dispatches.
  void Stop();
  // After the store thread drained: the links go.
  void Clear() { links_.clear(); }

 private:
  void OnAuthenticated(AgentLink& link);
  void OnAgentMessage(AgentLink& link, protocol::Message& message);
  void OnAgentClosed(AgentLink& link, const std::string& reason);
  void OnLeaseResult(AgentLink& link, const protocol::LeaseResultMsg& message);
  void OnLeaseReturn(AgentLink& link, const protocol::LeaseReturnMsg& message);
  void OnSceneRequest(AgentLink& link, const protocol::SceneRequestMsg& request);
  // The values of a display piece (job_display.cc); values that do not answer it convict the
  // agent.
  void OnPointResult(AgentLink& link, const protocol::PointResultMsg& result);
  void TakeLeasesAway(AgentLink& link, const char* why);
  // A result of `runner`'s job from `link` failed validation: a strike, maybe a blocklisting.
  void OnInvalidResult(AgentLink& link, RunningJob& runner, const std::string& why);
  // Whether `link`'s agent is blocklisted for `runner`'s job; if so, its scheduler is told.
  bool Blocklisted(AgentLink& link, RunningJob& runner, scheduler::TimePoint now);
  // Results of the job's gather ahead (gather_ahead.h): validated and kept there. False when the
  // link is closing (an invalid result, as for a round's).
  bool OnGatherAheadResults(AgentLink& link, RunningJob& runner,
                            const std::vector<const protocol::BatchOutcome*>& results);
  // Why `link`, just authenticated, may not stay (its name's connections, --max-agents), or
  // nothing.
  std::optional<std::string> RefusalOf(const AgentLink& link);
  // A refused or pre-authentication close, through the rate limiter.
  void LogAtDoor(const std::string& line);
  // Hands leases to one agent.
  void Dispatch(AgentLink& link);

  loop::EventLoop& loop_;
  const Clock& clock_;
  const MasterConfig& config_;
  const protocol::FarmSecret& secret_;
  const scheduler::SchedulerOptions& options_;
  StoreThread& store_;
  JobRounds& jobs_;

  std::map<uint64_t, std::unique_ptr<AgentLink>> links_;
  uint64_t next_agent_id_ = 1;
  JobBlocklist blocklist_;
  AgentCredentials credentials_;
  DoorKeeper doors_;
  std::shared_ptr<loop::FrameBudget> frame_budget_;
  LogRateLimiter door_log_;
  bool stopping_ = false;
};

}  // namespace radfarm::daemon
