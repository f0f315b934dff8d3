// Agent: the radfarm-agent daemon on its event loop. It keeps one authenticated connection to the
// master, reconnecting with backoff whenever it is lost, sends heartbeats, hands the master's work
// messages to its LeaseWorker, and decides when to stop (signals, Drain, --exit-when-idle).
//
// Connection states:
//
//   kWaiting --backoff timer--> kConnecting (name lookup on the I/O queue if the host is a name;
//             MasterLink: TCP, handshake) --Welcome--> kConnected
//   kConnecting, kConnected --link closed (any reason)--> leases dropped, kWaiting
//   any --Finish(): leases returned, Close(Shutdown) flushed--> kStopping --link closed or
//             deadline--> loop stopped
//   kWaiting, kConnecting, kConnected --idle policy: busy (leases returned, reason Overloaded;
//             connection closed)--> kPaused --idle policy: idle again--> kConnecting
//
// The idle policy ([idle] in the config file; idle/idle_monitor.h): with it the agent starts in
// kPaused and connects once the policy first says the machine is idle. When the policy says busy,
// the agent hands back every lease it holds (queued or running; a running batch's result is
// discarded when it comes back) and closes the connection, so the master neither waits for those
// batches nor leases it new ones; it stays disconnected until the policy says idle again. Without
// the policy the agent never pauses.
//
// systemd (a ServiceNotifier, when given): READY=1 once Start() succeeded, STATUS= on every state
// change and heartbeat ("connected to HOST:PORT, 3 leases, 120000 rays/s", "waiting: user
// active"), STOPPING=1 when an orderly stop begins.
//
// Threads: everything here runs on the loop thread. Batches run on the batch queue's --threads
// workers, scene loading and building on the I/O queue's one worker.
//
// Shutdown: after Run() returns, if busy() a batch or a scene build is still running on a worker;
// the process then exits without waiting for it (main uses _exit). Otherwise it destroys the Agent,
// which joins the idle workers, and closes the loop cleanly.
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "agent/agent_settings.h"
#include "agent/lease_worker.h"
#include "agent/master_link.h"
#include "agent/reconnect_backoff.h"
#include "agent/scene_store.h"
#include "idle/idle_monitor.h"
#include "loop/event_loop.h"
#include "loop/os_signal.h"
#include "loop/socket_address.h"
#include "loop/timer.h"
#include "loop/work_queue.h"
#include "protocol/farm_secret.h"
#include "service/service_notifier.h"

namespace radfarm::agent {

class Agent {
 public:
  // `systemd` may be null (no notifications); it must outlive the agent.
  Agent(loop::EventLoop& loop, AgentSettings settings, protocol::FarmSecret secret,
        std::optional<SceneStore> store, uint64_t jitter_seed,
        service::ServiceNotifier* systemd = nullptr);
  ~Agent();
  Agent(const Agent&) = delete;
  Agent& operator=(const Agent&) = delete;

  // Starts the work queues, watches SIGTERM and SIGINT, and makes the first connection attempt
  // (with the idle policy: starts the IdleMonitor, whose first "idle" makes it), then sends
  // READY=1.
  Status Start();
  // Work still running on a worker thread.
  bool busy() const { return resolving_ > 0 || (runner_ && runner_->busy()); }

 private:
  enum class State { kWaiting, kConnecting, kConnected, kPaused, kStopping };

  void StartAttempt();
  void Connect(const loop::SocketAddress& address);
  // Reads settings_.master_file on the I/O worker, then connects to the address it names.
  void ConnectFromMasterFile();
  void OnAuthenticated(const protocol::WelcomeMsg& welcome);
  void OnMessage(const protocol::Message& message);
  void OnLinkClosed(const LinkClosed& closed);
  // Logs why and tries again after the backoff's next delay, or `at_least` if that is longer.
  void ScheduleRetry(const std::string& what, const std::string& reason,
                     std::chrono::milliseconds at_least = std::chrono::milliseconds(0));

  // The idle policy's answer changed.
  void OnIdleChange(const idle::IdleDecision& decision);
  // Hands back every lease, closes the connection (or abandons the attempt) and waits.
  void Pause(const std::string& reason);
  void Resume(const std::string& reason);
  // A STATUS= line for systemd describing the current state.
  void ReportStatus();

  void OnDrain(const protocol::DrainMsg& drain);
  void OnLeasesChanged();
  void SendHeartbeat();
  void UpdateIdleTimer();
  void OnIdleTimeout();
  Status Send(const protocol::Message& message);

  // Returns the leases held, closes with Close(Shutdown) and stops the loop once that is written.
  void Finish(const std::string& reason);
  void StopLoop();

  loop::EventLoop& loop_;
  AgentSettings settings_;
  protocol::FarmSecret secret_;
  std::optional<SceneStore> store_;
  std::string master_;  // HOST:PORT as given or last read from the master file, for logs
  ReconnectBackoff backoff_;
  State state_ = State::kWaiting;
  // Attempts since the last connection that succeeded: one the master sent a message on after
  // its Welcome.
  uint32_t attempt_ = 0;
  bool draining_ = false;
  bool exit_when_drained_ = false;
  size_t resolving_ = 0;        // name lookups on the I/O queue
  bool may_work_ = true;        // the idle policy's latest answer (always true without one)
  bool ever_worked_ = false;    // the idle policy has said "idle" before (then "resuming")
  std::string waiting_reason_;  // why the agent is in kWaiting or kPaused, for STATUS=
  service::ServiceNotifier* systemd_;

  std::unique_ptr<loop::Timer> retry_timer_, heartbeat_timer_, idle_timer_, stop_deadline_;
  std::unique_ptr<loop::Signal> sigterm_, sigint_;
  std::unique_ptr<MasterLink> link_;
  std::unique_ptr<LeaseWorker> runner_;
  std::unique_ptr<idle::IdleMonitor> idle_monitor_;
  // Last, so they are destroyed first: their results point into this object.
  std::unique_ptr<loop::WorkQueue> io_, batches_;
};

}  // namespace radfarm::agent
