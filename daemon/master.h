// Master: the radfarmd daemon. It wires its parts together and owns the event loop's handles and
// the threads; each part has one job, in its room (README.md of each folder):
//
//   AgentConnections (agents/)   agent links, handshake, leases out, results in, heartbeats,
//                                stale and blocklisted agents
//   JobRounds (jobs/)            queued jobs started, rounds run, reduced and checkpointed, jobs
//                                finished or failed
//   StoreThread (jobs/)          the job store and the thread it runs on
//   ControlRequests (control/)   the control socket's requests
//   WebConsole (console/)        --http: status page, events, /metrics, actions
//
// They read the time through a Clock (jobs/clock.h): here the loop's, in tests a fake one.
//
// Threads. One event loop (the loop thread) runs the agent listener, the control socket, the
// heartbeat and lease timers and every job's RoundScheduler; every part lives on it. SQLite runs
// on the store thread (a one-thread WorkQueue that owns the JobStore) and meshing and round
// reductions on the compute thread (another); both hand their results back through the loop.
//
// Jobs: queued jobs start (up to max_running_jobs) by priority, then submission. A running job
// leases its rounds' batches to agents; after each round the compute thread reduces it and plans
// the next, and the store thread commits the round (and a checkpoint) while agents already work on
// the next. A restarted master puts its running jobs back in the queue and resumes each from its
// latest checkpoint, so the output is the same as without the restart.
#pragma once

#include <memory>
#include <string>

#include "base/result.h"
#include "daemon/agents/agent_connections.h"
#include "daemon/config/master_config.h"
#include "daemon/console/web_console.h"
#include "daemon/control/control_requests.h"
#include "daemon/control/control_server.h"
#include "daemon/jobs/clock.h"
#include "daemon/jobs/job_rounds.h"
#include "daemon/jobs/store_thread.h"
#include "daemon/scheduler/round_scheduler.h"
#include "loop/event_loop.h"
#include "loop/os_signal.h"
#include "loop/tcp_listener.h"
#include "loop/timer.h"
#include "loop/work_queue.h"
#include "protocol/farm_secret.h"
#include "service/service_notifier.h"

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

  const std::string& listen_address() const { return listen_address_; }

 private:
  Master(loop::EventLoop& loop, const MasterConfig& config, protocol::FarmSecret secret);
  // Creates the parts and the handles that feed them.
  Status Wire(const std::vector<store::AgentCredential>& credentials);
  void OnHeartbeatTimer();
  void OnTickTimer();
  // "2 jobs running, 1 starting; 5 agents" for systemd's STATUS=.
  void ReportStatus();

  loop::EventLoop& loop_;
  const MasterConfig config_;
  const protocol::FarmSecret secret_;
  const LoopClock clock_;  // the rooms' time: the loop's
  scheduler::SchedulerOptions scheduler_options_;
  // The threads, then the parts that use them, then the handles that call the parts.
  std::unique_ptr<StoreThread> store_;
  std::unique_ptr<loop::WorkQueue> compute_;
  std::unique_ptr<JobRounds> jobs_;
  std::unique_ptr<AgentConnections> agents_;
  std::unique_ptr<ControlRequests> control_;
  std::unique_ptr<loop::TcpListener> listener_;
  std::unique_ptr<ControlServer> control_server_;
  std::unique_ptr<WebConsole> web_;  // --http only
  std::unique_ptr<loop::Timer> heartbeat_timer_;
  std::unique_ptr<loop::Timer> tick_timer_;
  std::unique_ptr<loop::Signal> sigterm_;
  std::unique_ptr<loop::Signal> sigint_;
  std::unique_ptr<service::ServiceNotifier> notifier_;  // systemd: READY, STATUS, watchdog
  std::string listen_address_;
  bool shutting_down_ = false;
};

}  // namespace radfarm::daemon
