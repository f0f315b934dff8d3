// MasterParts: the master's middle (JobRounds, AgentConnections, ControlRequests) wired as Master
// wires it, inside the test's process: a real event loop, store thread (a job store in a
// temporary directory) and compute thread, the agents' listener on a loopback port, and a
// FakeClock in place of the loop's, so that a test moves time by hand (LevelDB's Env, our
// scheduler tests' kT0). A test acts through control requests, fake agents (fake_agent.h) and the
// clock, and waits on conditions (RunUntil), never on time. The destructor stops the parts as
// Master::Shutdown does and proves the loop closes clean.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "daemon/agents/agent_connections.h"
#include "daemon/config/master_config.h"
#include "daemon/control/control_requests.h"
#include "daemon/jobs/clock.h"
#include "daemon/jobs/job_rounds.h"
#include "daemon/jobs/store_thread.h"
#include "daemon/scheduler/scheduler_options.h"
#include "loop/event_loop.h"
#include "loop/socket_address.h"
#include "loop/tcp_listener.h"
#include "loop/work_queue.h"
#include "protocol/farm_secret.h"
#include "testing/temp_dir.h"

namespace radfarm::daemon::fakes {

class FakeClock final : public Clock {
 public:
  uint64_t NowMs() const override { return now_ms_; }
  void Advance(std::chrono::milliseconds by) { now_ms_ += uint64_t(by.count()); }

 private:
  uint64_t now_ms_ = 1'000'000;  // any origin: the rooms only compare and subtract times
};

// radfarmd's defaults, but every round leased to agents (no local rounds, no gather ahead) and no
// exact validation, so that what the fake agents send is all that happens to a round.
MasterConfig TestMasterConfig();

// A job bundle of the Cornell box at a coarse patch size, its ray budget `max_rays` (0: none),
// with `gather_rays` of final gather (0: none, so the budget ends the job, and the display has
// no direct light to start from: the patches' averages, no ray).
std::vector<uint8_t> CornellBundle(uint64_t max_rays, uint32_t gather_rays = 0);

class MasterParts {
 public:
  explicit MasterParts(const MasterConfig& config = TestMasterConfig());
  ~MasterParts();
  MasterParts(const MasterParts&) = delete;
  MasterParts& operator=(const MasterParts&) = delete;

  // Runs the loop until `done()` holds; false if it never does (a generous bound, not a timing).
  bool RunUntil(const std::function<bool()>& done);
  // Hands `request` to ControlRequests and runs the loop until it is answered.
  ControlResponse Request(ControlRequest request);
  // `command` with `id`, answered.
  ControlResponse Request(ControlCommand command, uint64_t id);
  // Submits CornellBundle(max_rays, gather_rays); returns the new job's id (0 if refused: a test
  // failure).
  uint64_t Submit(uint64_t max_rays, int64_t priority = 0, uint32_t gather_rays = 0);
  // The job's state as `status` answers it ("queued", "running", ...).
  std::string StateOf(uint64_t id);

  loop::EventLoop& loop() { return loop_; }
  FakeClock& clock() { return clock_; }
  const MasterConfig& config() const { return config_; }
  JobRounds& jobs() { return *jobs_; }
  AgentConnections& agents() { return *agents_; }
  ControlRequests& control() { return *control_; }
  const protocol::FarmSecret& secret() const { return secret_; }
  // Where fake agents connect.
  const loop::SocketAddress& agent_address() const { return *agent_address_; }

 private:
  radfarm::testing::TempDir state_;
  MasterConfig config_;
  protocol::FarmSecret secret_;
  scheduler::SchedulerOptions options_;
  loop::EventLoop loop_;
  FakeClock clock_;
  std::unique_ptr<StoreThread> store_;
  std::unique_ptr<loop::WorkQueue> compute_;
  std::unique_ptr<JobRounds> jobs_;
  std::unique_ptr<AgentConnections> agents_;
  std::unique_ptr<ControlRequests> control_;
  std::unique_ptr<loop::TcpListener> listener_;
  std::optional<loop::SocketAddress> agent_address_;  // set once the listener is bound
};

}  // namespace radfarm::daemon::fakes
