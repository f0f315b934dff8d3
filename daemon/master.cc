#include "daemon/master.h"

#include <signal.h>

#include <algorithm>
#include <filesystem>
#include <system_error>

#include "base/atomic_file.h"
#include "base/private_dir.h"
#include "base/result.h"
#include "loop/log.h"
#include "store/job_transactions.h"

namespace radfarm::daemon {

Master::Master(loop::EventLoop& loop, const MasterConfig& config, protocol::FarmSecret secret)
    : loop_(loop), config_(config), secret_(std::move(secret)), clock_(loop) {
  scheduler_options_.target_lease_seconds = config.lease_seconds;
  // A lease is overdue (offered to another agent too) once it takes several times its expected
  // time, but never sooner than the time an agent may stay silent.
  scheduler_options_.deadline_floor = std::chrono::milliseconds(config.agent_timeout_ms);
  scheduler_options_.blocklist_duration = std::chrono::seconds(config.blocklist_seconds);
  // One lease queued behind the running ones: an agent holding only what fills lease_seconds
  // (usually one batch) idles for a round trip after every batch, most of its time under latency
  // (farm_bench's simulated agents).
  scheduler_options_.spare_leases = 1;
  // Leases go out many batches to a frame (protocol version 2): an agent holds what fills
  // lease_seconds at its own speed, and a quarter more, so that the next lease is there when one
  // ends (a lease is answered when all its batches are done) but a lower-priority job queues
  // little ahead of a higher one.
  scheduler_options_.spare_lease_fraction = 0.25;
  // At most half a lease frame (kMaxLeaseBatches) held: an agent keeps a record of every held
  // batch, and a budget's paced rounds of shots of a few rays would fill its lease time with a
  // frame's worth of them, a large share of its peak memory (docs/SCALING.md).
  scheduler_options_.max_leases_per_agent = 1u << 15;
  // Near a round's end an agent holds no more than it finishes by the round's predicted end: the
  // first agents asked would otherwise hold the final gather's round long past its work's time.
  scheduler_options_.round_end_share = 1;
  // An agent holds at least 0.1 s of work where it can, so that the tapered end of a round (pieces
  // too small for a lease capacity of them to cover the round trip) does not idle it for a round
  // trip after each lease (docs/BENCHMARKS-farm.md).
  scheduler_options_.min_held_seconds = 0.1;
  scheduler_options_.gather_ahead_rays = config.gather_ahead_rays;
}

Master::~Master() = default;

Result<std::unique_ptr<Master>> Master::Start(loop::EventLoop& loop, const MasterConfig& config,
                                              protocol::FarmSecret secret) {
  // Private whatever the umask: it holds the job store and the control socket.
  if (Status made = CreatePrivateDirectories(config.state_dir); !made.ok()) {
    return Error{"state directory " + made.error()};
  }
  std::unique_ptr<Master> master(new Master(loop, config, std::move(secret)));

  store::JobStoreOptions store_options;
  // SQLite counts pages of 4 KiB (its default page size, which the store keeps).
  if (config.max_store_bytes > 0) {
    store_options.max_pages = std::max<int64_t>(1, int64_t(config.max_store_bytes / 4096));
  }
  Result<store::JobStore> store = store::JobStore::Open(config.DatabasePath(), store_options);
  RADFARM_RETURN_IF_ERROR(store);
  // Jobs that were running when the last master stopped go back to the queue; they resume from
  // their latest checkpoints when they start again.
  if (Result<int> requeued = store::RequeueRunningJobs(*store); !requeued) {
    return Error{requeued.error()};
  }
  // Kept results of jobs that ended just before the last master stopped (JobRounds::FinishJob).
  RADFARM_RETURN_IF_ERROR(store->PruneEndedJobsRoundResults());
  // Read here, once: from now on the handshake uses the in-memory copy (agent_credentials.h).
  Result<std::vector<store::AgentCredential>> credentials = store->ListAgentCredentials();
  RADFARM_RETURN_IF_ERROR(credentials);
  auto store_thread = StoreThread::Start(loop, std::move(*store));
  RADFARM_RETURN_IF_ERROR(store_thread);
  master->store_ = std::move(*store_thread);
  auto compute = loop::WorkQueue::Create(loop, 1, "compute");
  RADFARM_RETURN_IF_ERROR(compute);
  master->compute_ = std::move(*compute);
  if (Status s = master->Wire(*credentials); !s) return Error{s.error()};

  master->notifier_ = std::make_unique<service::ServiceNotifier>(loop);
  master->notifier_->Ready();  // the store is open and both listeners are bound
  master->ReportStatus();
  loop::LogLine(loop::LogLevel::kInfo, "master")
      << "listening for agents on " << master->listen_address_ << "; control socket "
      << master->control_server_->path() << "; state " << config.state_dir;
  master->jobs_->StartQueuedJobs();
  return master;
}

Status Master::Wire(const std::vector<store::AgentCredential>& credentials) {
  // JobRounds reaches the agents only through these hooks (agents_ is made right after it).
  AgentHooks hooks{[this] { agents_->DispatchAll(); },
                   [this](store::JobId id) { agents_->CancelJob(id); },
                   [this] { return agents_->Available(); },
                   [this] { return agents_->ReportedRaysPerSecond(); },
                   [this](store::JobId id, const std::string& agent, const std::string& why) {
                     agents_->Convict(id, agent, why);
                   },
                   [this] { return agents_->PointAgents(protocol::kPointLeaseVersion); },
                   [this] { return agents_->PointAgents(protocol::kStartLeaseVersion); },
                   [this] { return agents_->PointAgents(protocol::kSkyVersion); }};
  jobs_ = std::make_unique<JobRounds>(loop_, clock_, config_, scheduler_options_, *store_,
                                      *compute_, std::move(hooks));
  agents_ = std::make_unique<AgentConnections>(loop_, clock_, config_, secret_, scheduler_options_,
                                               *store_, *jobs_, credentials);
  control_ = std::make_unique<ControlRequests>(clock_, *store_, *compute_, *jobs_, *agents_);

  Result<loop::HostPort> listen = loop::ParseHostPort(config_.listen, "--listen");
  RADFARM_RETURN_IF_ERROR(listen);
  AgentConnections* agents = agents_.get();
  auto listener = loop::TcpListener::Listen(
      loop_, *listen,
      [agents](std::unique_ptr<loop::FramedConnection> c) { agents->OnConnection(std::move(c)); });
  RADFARM_RETURN_IF_ERROR(listener);
  listener_ = std::move(*listener);
  listen_address_ = listener_->address();

  ControlRequests* control = control_.get();
  auto control_server = ControlServer::Listen(
      loop_, config_.ControlPath(),
      [control](ControlRequest request, ControlRespond respond) {
        control->Handle(std::move(request), std::move(respond));
      },
      ControlServerOptions{std::chrono::milliseconds(config_.control_timeout_ms)});
  RADFARM_RETURN_IF_ERROR(control_server);
  control_server_ = std::move(*control_server);
  if (!config_.http.empty()) {
    auto web = WebConsole::Start(loop_, config_, *control_, *jobs_, *store_);
    RADFARM_RETURN_IF_ERROR(web);
    web_ = std::move(*web);
  }
  // listen.addr last: whoever waits for it (scripts, tests, the README) may use the control
  // socket at once.
  if (Status s = WriteFileAtomically(config_.ListenAddrPath(), listen_address_ + "\n"); !s) {
    return Error{s.error()};
  }

  heartbeat_timer_ = std::make_unique<loop::Timer>(loop_);
  heartbeat_timer_->Start(std::chrono::milliseconds(config_.heartbeat_ms),
                          std::chrono::milliseconds(config_.heartbeat_ms),
                          [this] { OnHeartbeatTimer(); });
  tick_timer_ = std::make_unique<loop::Timer>(loop_);
  tick_timer_->Start(std::chrono::milliseconds(100), std::chrono::milliseconds(100),
                     [this] { OnTickTimer(); });
  for (int signum : {SIGTERM, SIGINT}) {
    auto watch = loop::Signal::Watch(
        loop_, signum, [this](int s) { Shutdown(s == SIGTERM ? "SIGTERM" : "SIGINT"); });
    RADFARM_RETURN_IF_ERROR(watch);
    (signum == SIGTERM ? sigterm_ : sigint_) = std::move(*watch);
  }
  return Ok{};
}

void Master::Shutdown(const std::string& why) {
  if (shutting_down_) return;
  shutting_down_ = true;
  loop::LogLine(loop::LogLevel::kInfo, "master") << why << ": shutting down";
  notifier_->Stopping();
  if (web_) web_->Stop();  // first: no HTTP thread may wait on the loop from here on
  agents_->Stop();         // agents keep their state and reconnect to the next master by themselves
  jobs_->Stop();
  control_->Stop();
  listener_->Close();
  control_server_->Close();
  heartbeat_timer_->Close();
  tick_timer_->Close();
  sigterm_->Close();
  sigint_->Close();
  compute_->Shutdown(loop::WorkQueue::ShutdownMode::kCancel, [] {});
  // Let committed-to writes finish: a checkpoint in flight is either written whole or not at all.
  store_->Drain([this] {
    agents_->Clear();
    jobs_->Clear();
    loop_.Stop();
  });
}

void Master::OnHeartbeatTimer() {
  ReportStatus();
  agents_->Heartbeat();
}

void Master::OnTickTimer() {
  if (jobs_->Tick(clock_.Now()) > 0 || jobs_->InEndGame() || jobs_->LeasingPoints()) {
    agents_->DispatchAll();
  }
  jobs_->RetryHeldJobs(clock_.NowMs());
}

void Master::ReportStatus() {
  notifier_->Status(std::to_string(jobs_->runners().size()) + " jobs running, " +
                    std::to_string(jobs_->starting()) + " starting; " +
                    std::to_string(agents_->active()) + " agents");
}

}  // namespace radfarm::daemon
