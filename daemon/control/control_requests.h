// ControlRequests: the master's answers to the control socket's requests (docs/CONTROL.md):
// submit, list, status, cancel, pause, resume, log, fetch, agents, enroll_agent, revoke_agent. A
// request that reads or writes the store runs one of the store's named transactions
// (store/job_transactions.h) on the store thread and answers when it is committed; a submitted
// bundle is decoded and meshed on the compute thread first, so one the agents could not use is
// refused at once. Live figures (rays per second, agents, ETA) come from the running jobs
// (JobRounds).
//
// Loop thread only.
#pragma once

#include <map>
#include <nlohmann/json.hpp>

#include "core/progress_ratchet.h"
#include "daemon/agents/agent_connections.h"
#include "daemon/control/control_types.h"
#include "daemon/control/job_summary.h"
#include "daemon/jobs/clock.h"
#include "daemon/jobs/job_rounds.h"
#include "daemon/jobs/store_thread.h"
#include "loop/event_loop.h"
#include "loop/work_queue.h"

namespace radfarm::daemon {

class ControlRequests {
 public:
  ControlRequests(const Clock& clock, StoreThread& store, loop::WorkQueue& compute, JobRounds& jobs,
                  AgentConnections& agents);
  ControlRequests(const ControlRequests&) = delete;
  ControlRequests& operator=(const ControlRequests&) = delete;

  // The control server's callback.
  void Handle(ControlRequest request, ControlRespond respond);
  // Shutdown: every later request is answered with an error.
  void Stop() { stopping_ = true; }

 private:
  nlohmann::json JobJson(const JobSummary& summary);
  // The progress shown for a job whose progress is estimated at `estimate` now: never less than
  // shown before while the job lives (core/progress_ratchet.h), whatever its phase (preparing,
  // rounds, reducing, display, paused); at most kProgressBeforeDone until the job is done, 1 once
  // done. A job that ended is forgotten.
  double ShownProgress(const store::JobRecord& record, double estimate);
  static constexpr double kProgressBeforeDone = 0.99;
  nlohmann::json AgentJson(const AgentLink& link) const;
  // `enrolled_agents`: every enrolled name, its state and how many of its connections are in.
  nlohmann::json EnrolledJson() const;
  // The door counters (agent_connections.h, door_keeper.h): `agents`' "connections" object.
  nlohmann::json DoorsJson() const;
  void Submit(ControlRequest request, ControlRespond respond);
  void ChangeState(ControlRequest request, ControlRespond respond);
  void Fetch(ControlRequest request, ControlRespond respond);
  void Log(ControlRequest request, ControlRespond respond);
  // `radfarm agents enroll|revoke NAME`: the store first, then the in-memory credentials.
  void EnrollAgent(const std::string& name, ControlRespond respond);
  void RevokeAgent(const std::string& name, ControlRespond respond);
  // Answers with the job object of `id` (all jobs when nullopt) read from the store.
  void RespondWithJobs(std::optional<store::JobId> id, ControlRespond respond);

  const Clock& clock_;
  StoreThread& store_;
  loop::WorkQueue& compute_;
  JobRounds& jobs_;
  AgentConnections& agents_;
  bool stopping_ = false;
  // Loop thread: the progress shown so far of each job not ended that status has shown.
  std::map<store::JobId, ProgressRatchet> shown_progress_;
};

}  // namespace radfarm::daemon
