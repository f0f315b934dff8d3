// Master: the radfarmd daemon. One event loop (the loop thread) runs the agent listener, the
// control socket, the heartbeat and lease timers and every job's RoundScheduler. SQLite runs on
// the store thread (a one-thread WorkQueue that owns the JobStore) and meshing and round
// reductions on the compute thread; both hand their results back through the loop.
//
// Jobs: queued jobs start (up to max_running_jobs) by priority, then submission. A running job
// leases its rounds' batches to agents; after each round the compute thread reduces it and plans
// the next, and the store thread commits the round (and a checkpoint) while agents already work on
// the next. A restarted master puts its running jobs back in the queue and resumes each from its
// latest checkpoint, so the output is the same as without the restart.
//
// Files: master.cc (start, stop, timers), master_agents.cc (connections, leases, results),
// master_jobs.cc (job lifecycle, rounds, checkpoints), master_control.cc (control requests).
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "daemon/agent_link.h"
#include "daemon/control_server.h"
#include "daemon/control_types.h"
#include "daemon/job_runner.h"
#include "daemon/job_summary.h"
#include "daemon/master_config.h"
#include "daemon/scheduler/round_scheduler.h"
#include "loop/event_loop.h"
#include "loop/log.h"
#include "loop/os_signal.h"
#include "loop/tcp_listener.h"
#include "loop/timer.h"
#include "loop/work_queue.h"
#include "protocol/farm_secret.h"
#include "service/service_notifier.h"
#include "store/job_store.h"

namespace radfarm::daemon {

class Master {
 public:
  // Opens the store (checks and migrates it), binds the listeners, writes STATE/listen.addr.
  // Runs before the loop does, so it may block.
  static Result<std::unique_ptr<Master>> Start(loop::EventLoop& loop, const MasterConfig& config,
                                               protocol::FarmSecret secret);
  ~Master();
  Master(const Master&) = delete;
  Master& operator=(const Master&) = delete;

  // Begins an orderly stop (SIGTERM): agents are told, the store queue drains, the loop ends.
  void Shutdown(const std::string& why);

  // The control socket's entry point (master_control.cc).
  void HandleControl(ControlRequest request, ControlRespond respond);

  const std::string& listen_address() const { return listen_address_; }

 private:
  using TimePoint = scheduler::TimePoint;
  using StoreRef = std::shared_ptr<store::JobStore>;

  Master(loop::EventLoop& loop, const MasterConfig& config, protocol::FarmSecret secret);
  TimePoint Now() const;

  // --- agents (master_agents.cc) ---
  void OnConnection(std::unique_ptr<loop::FramedConnection> connection);
  void OnAuthenticated(AgentLink& link);
  void OnAgentMessage(AgentLink& link, protocol::Message& message);
  void OnAgentClosed(AgentLink& link, const std::string& reason);
  void OnBatchResult(AgentLink& link, const protocol::BatchResultMsg& result);
  void OnLeaseReturn(AgentLink& link, const protocol::LeaseReturnMsg& message);
  void OnSceneRequest(AgentLink& link, const protocol::SceneRequestMsg& request);
  void TakeLeasesAway(AgentLink& link, const char* why);
  // Hands leases to one agent / to every agent with room.
  void Dispatch(AgentLink& link);
  void DispatchAll();
  void OnHeartbeatTimer();
  void OnTickTimer();
  // "2 jobs running, 1 queued; 5 agents" for systemd's STATUS= and the log.
  void ReportStatus();
  void Blocklist(AgentLink& link, const std::string& why);

  // --- jobs (master_jobs.cc) ---
  void StartQueuedJobs();
  void OnJobPrepared(store::JobId id, Result<std::shared_ptr<JobRunner>> runner);
  // Starts the planned round on the agents, or computes it here when it is small
  // (MasterConfig::local_round_rays).
  void BeginRound(const std::shared_ptr<JobRunner>& runner);
  void RunRoundHere(const std::shared_ptr<JobRunner>& runner);
  void OnRoundComplete(const std::shared_ptr<JobRunner>& runner);
  // `work` (Reduce, perhaps after RunLocally) on the compute thread, then OnRoundReduced.
  void ReduceOnComputeThread(const std::shared_ptr<JobRunner>& runner,
                             std::function<RoundOutcome()> work);
  // Whether the round about to be reduced checkpoints (every round, or every checkpoint_seconds).
  bool CheckpointDue(store::JobId id);
  void OnRoundReduced(const std::shared_ptr<JobRunner>& runner, RoundOutcome outcome);
  void FinishJob(const std::shared_ptr<JobRunner>& runner, store::JobState state,
                 std::optional<std::string> error);
  // Stops a job's work on every agent (Cancel) and forgets its runner.
  void DropRunner(store::JobId id);
  void FailJob(store::JobId id, const std::string& error);
  std::vector<JobRunner*> RunnersByPriority();
  JobRunner* FindRunner(uint64_t job_id);
  // Queues `work(JobStore&)` on the store thread; `done` gets its result on the loop thread.
  template <typename Work, typename Done>
  void OnStore(Work work, Done done);
  void LogEvent(std::optional<store::JobId> job, store::EventLevel level, const std::string& text);

  // --- control (master_control.cc) ---
  nlohmann::json JobJson(const JobSummary& summary);
  nlohmann::json AgentJson(const AgentLink& link) const;
  void Submit(ControlRequest request, ControlRespond respond);
  void ChangeState(ControlRequest request, ControlRespond respond);
  void Fetch(ControlRequest request, ControlRespond respond);
  // Answers with the job objects of `ids` (all jobs when empty) read from the store.
  void RespondWithJobs(std::optional<store::JobId> id, ControlRespond respond);

  loop::EventLoop& loop_;
  MasterConfig config_;
  protocol::FarmSecret secret_;
  scheduler::SchedulerOptions scheduler_options_;
  StoreRef store_;  // used on the store thread only
  std::unique_ptr<loop::WorkQueue> store_queue_;
  std::unique_ptr<loop::WorkQueue> compute_queue_;
  std::unique_ptr<loop::TcpListener> listener_;
  std::unique_ptr<ControlServer> control_;
  std::unique_ptr<loop::Timer> heartbeat_timer_;
  std::unique_ptr<loop::Timer> tick_timer_;
  std::unique_ptr<loop::Signal> sigterm_;
  std::unique_ptr<loop::Signal> sigint_;
  std::unique_ptr<service::ServiceNotifier> notifier_;  // systemd: READY, STATUS, watchdog
  std::string listen_address_;

  std::map<uint64_t, std::unique_ptr<AgentLink>> agents_;
  uint64_t next_agent_id_ = 1;
  std::unordered_map<std::string, TimePoint> blocklist_;  // agent name -> until
  std::map<store::JobId, std::shared_ptr<JobRunner>> runners_;
  std::map<store::JobId, uint64_t> last_checkpoint_ms_;  // loop NowMs() of each job's last one
  std::map<store::JobId, bool> starting_;  // being prepared; true once cancelled meanwhile
  bool start_pending_ = false;             // a StartQueuedJobs query is in flight
  bool start_again_ = false;               // ... and another was asked for meanwhile
  size_t dispatch_rotation_ = 0;
  bool shutting_down_ = false;
};

template <typename Work, typename Done>
void Master::OnStore(Work work, Done done) {
  StoreRef store = store_;
  Status s = store_queue_->Submit(
      [store, work = std::move(work)]() mutable { return work(*store); }, std::move(done));
  if (!s)
    loop::Log(loop::LogLevel::kError, "store", "cannot queue a store operation: " + s.error());
}

}  // namespace radfarm::daemon
