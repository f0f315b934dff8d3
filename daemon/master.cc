#include "daemon/master.h"

#include <signal.h>

#include <filesystem>
#include <system_error>

#include "loop/log.h"
#include "output/atomic_file.h"
#include "store/job_transactions.h"

namespace radfarm::daemon {

Master::Master(loop::EventLoop& loop, const MasterConfig& config, protocol::FarmSecret secret)
    : loop_(loop), config_(config), secret_(std::move(secret)) {
  scheduler_options_.target_lease_seconds = config.lease_seconds;
  // A lease is overdue (offered to another agent too) once it takes several times its expected
  // time, but never sooner than the time an agent may stay silent.
  scheduler_options_.deadline_floor = std::chrono::milliseconds(config.agent_timeout_ms);
  // One lease queued behind the running ones: an agent holding only what fills lease_seconds
  // (usually one batch) idles for a round trip after every batch. farm_bench measured it with 1000
  // simulated agents: 38 % of their time idle mid-round on loopback, 68 % with 20 ms latency.
  scheduler_options_.spare_leases = 1;
}

Master::~Master() = default;

scheduler::TimePoint Master::Now() const {
  return scheduler::TimePoint(std::chrono::milliseconds(loop_.NowMs()));
}

Result<std::unique_ptr<Master>> Master::Start(loop::EventLoop& loop, const MasterConfig& config,
                                              protocol::FarmSecret secret) {
  std::error_code ec;
  std::filesystem::create_directories(config.state_dir, ec);
  if (ec) {
    return Error{"state directory " + config.state_dir + ": cannot create it: " + ec.message()};
  }
  std::unique_ptr<Master> master(new Master(loop, config, std::move(secret)));
  Master* self = master.get();

  Result<store::JobStore> store = store::JobStore::Open(config.DatabasePath());
  if (!store) return Error{store.error()};
  // Jobs that were running when the last master stopped go back to the queue; they resume from
  // their latest checkpoints when they start again.
  if (Result<int> requeued = store::RequeueRunningJobs(*store); !requeued) {
    return Error{requeued.error()};
  }
  master->store_ = std::make_shared<store::JobStore>(std::move(*store));

  auto store_queue = loop::WorkQueue::Create(loop, 1, "store");
  if (!store_queue) return Error{store_queue.error()};
  master->store_queue_ = std::move(*store_queue);
  auto compute_queue = loop::WorkQueue::Create(loop, 1, "compute");
  if (!compute_queue) return Error{compute_queue.error()};
  master->compute_queue_ = std::move(*compute_queue);

  Result<loop::HostPort> listen = loop::ParseHostPort(config.listen, "--listen");
  if (!listen) return Error{listen.error()};
  auto listener = loop::TcpListener::Listen(
      loop, *listen,
      [self](std::unique_ptr<loop::FramedConnection> c) { self->OnConnection(std::move(c)); });
  if (!listener) return Error{listener.error()};
  master->listener_ = std::move(*listener);
  master->listen_address_ = master->listener_->address();
  if (Status s = WriteFileAtomically(config.ListenAddrPath(), master->listen_address_ + "\n"); !s) {
    return Error{s.error()};
  }

  auto control = ControlServer::Listen(
      loop, config.ControlPath(), [self](ControlRequest request, ControlRespond respond) {
        self->HandleControl(std::move(request), std::move(respond));
      });
  if (!control) return Error{control.error()};
  master->control_ = std::move(*control);

  master->heartbeat_timer_ = std::make_unique<loop::Timer>(loop);
  master->heartbeat_timer_->Start(std::chrono::milliseconds(config.heartbeat_ms),
                                  std::chrono::milliseconds(config.heartbeat_ms),
                                  [self] { self->OnHeartbeatTimer(); });
  master->tick_timer_ = std::make_unique<loop::Timer>(loop);
  master->tick_timer_->Start(std::chrono::milliseconds(100), std::chrono::milliseconds(100),
                             [self] { self->OnTickTimer(); });
  for (int signum : {SIGTERM, SIGINT}) {
    auto watch = loop::Signal::Watch(
        loop, signum, [self](int s) { self->Shutdown(s == SIGTERM ? "SIGTERM" : "SIGINT"); });
    if (!watch) return Error{watch.error()};
    (signum == SIGTERM ? master->sigterm_ : master->sigint_) = std::move(*watch);
  }

  master->notifier_ = std::make_unique<service::ServiceNotifier>(loop);
  master->notifier_->Ready();  // the store is open and both listeners are bound
  master->ReportStatus();
  loop::LogLine(loop::LogLevel::kInfo, "master")
      << "listening for agents on " << master->listen_address_ << "; control socket "
      << master->control_->path() << "; state " << config.state_dir;
  master->StartQueuedJobs();
  return master;
}

void Master::Shutdown(const std::string& why) {
  if (shutting_down_) return;
  shutting_down_ = true;
  loop::LogLine(loop::LogLevel::kInfo, "master") << why << ": shutting down";
  notifier_->Stopping();
  // Agents keep their state; they reconnect to the next master by themselves.
  for (auto& [id, link] : agents_) {
    if (link->authenticated()) link->Close(protocol::CloseCode::kShutdown, "master shutting down");
  }
  listener_->Close();
  control_->Close();
  heartbeat_timer_->Close();
  tick_timer_->Close();
  sigterm_->Close();
  sigint_->Close();
  compute_queue_->Shutdown(loop::WorkQueue::ShutdownMode::kCancel, [] {});
  // Let committed-to writes finish: a checkpoint in flight is either written whole or not at all.
  store_queue_->Shutdown(loop::WorkQueue::ShutdownMode::kDrain, [this] {
    agents_.clear();
    runners_.clear();
    loop_.Stop();
  });
}

void Master::ReportStatus() {
  size_t agents = 0;
  for (const auto& [id, link] : agents_) agents += link->authenticated() && !link->stale();
  notifier_->Status(std::to_string(runners_.size()) + " jobs running, " +
                    std::to_string(starting_.size()) + " starting; " + std::to_string(agents) +
                    " agents");
}

}  // namespace radfarm::daemon
