#include "agent/agent.h"

#include <algorithm>
#include <csignal>
#include <cstdlib>
#include <sstream>
#include <variant>

#include "agent/file_user_idle.h"
#include "agent/master_address.h"
#include "base/result.h"
#include "loop/log.h"
#include "protocol/limits.h"
#include "protocol/messages.h"

namespace radfarm::agent {
namespace {

using loop::LogLevel;
using loop::LogLine;
using std::chrono::milliseconds;

// How long the last frames (LeaseReturn, Close) may take to leave at shutdown, and the hard stop
// after which the agent exits anyway: well within the one second it promises.
constexpr milliseconds kFlushTimeout{500};
constexpr milliseconds kStopDeadline{900};
constexpr milliseconds kHandshakeTimeout{10000};
// After Close(Blocklisted): the master refuses this agent work of a job for minutes
// (radfarmd --blocklist-seconds); a minute between attempts keeps its log readable.
constexpr milliseconds kBlocklistedRetry{60000};

// The 1-minute load average; 0 where the system does not say.
double LoadAverage() {
  double load[1] = {0};
  return getloadavg(load, 1) == 1 && load[0] >= 0 ? load[0] : 0;
}

// A Close detail: printable ASCII, at most 256 bytes.
std::string CloseDetail(const std::string& text) {
  std::string detail;
  for (char c : text.substr(0, 200)) detail += (c >= 0x20 && c < 0x7f) ? c : '?';
  return detail;
}

}  // namespace

Agent::Agent(loop::EventLoop& loop, AgentSettings settings, protocol::FarmSecret secret,
             std::optional<SceneStore> store, uint64_t jitter_seed,
             service::ServiceNotifier* systemd)
    : loop_(loop),
      settings_(std::move(settings)),
      secret_(std::move(secret)),
      store_(std::move(store)),
      master_(settings_.master_file.empty() ? settings_.master.ToString()
                                            : "the master in " + settings_.master_file),
      backoff_(ReconnectBackoff::Options{}, jitter_seed),
      systemd_(systemd) {}

Agent::~Agent() = default;

Status Agent::Start() {
  Result<std::unique_ptr<loop::WorkQueue>> batches =
      loop::WorkQueue::Create(loop_, settings_.threads, "batch");
  RADFARM_RETURN_IF_ERROR(batches);
  batches_ = std::move(batches).value();
  Result<std::unique_ptr<loop::WorkQueue>> io = loop::WorkQueue::Create(loop_, 1, "scene-io");
  RADFARM_RETURN_IF_ERROR(io);
  io_ = std::move(io).value();

  LeaseWorker::Callbacks callbacks;
  callbacks.send = [this](const protocol::Message& message) { return Send(message); };
  callbacks.protocol_version = [this] {
    return link_ ? link_->version() : protocol::kProtocolVersion;
  };
  callbacks.on_leases_changed = [this] { OnLeasesChanged(); };
  runner_ = std::make_unique<LeaseWorker>(loop_, settings_, *batches_, *io_, std::move(store_),
                                          master_, std::move(callbacks));

  retry_timer_ = std::make_unique<loop::Timer>(loop_);
  heartbeat_timer_ = std::make_unique<loop::Timer>(loop_);
  idle_timer_ = std::make_unique<loop::Timer>(loop_);
  stop_deadline_ = std::make_unique<loop::Timer>(loop_);
  for (auto [signum, watch] : {std::pair{SIGTERM, &sigterm_}, std::pair{SIGINT, &sigint_}}) {
    Result<std::unique_ptr<loop::Signal>> signal =
        loop::Signal::Watch(loop_, signum, [this](int s) {
          if (state_ == State::kStopping) {
            LogLine(LogLevel::kWarning, "agent") << "second signal: stopping now";
            StopLoop();
            return;
          }
          Finish(s == SIGTERM ? "got SIGTERM" : "got SIGINT");
        });
    RADFARM_RETURN_IF_ERROR(signal);
    *watch = std::move(signal).value();
  }
  LogLine(LogLevel::kInfo, "agent") << "radfarm-agent " << settings_.name << " starting: master "
                                    << master_ << ", " << settings_.threads << " threads"
                                    << (settings_.idle_policy_enabled() ? ", idle policy on" : "");
  if (settings_.idle_policy_enabled()) {
    // The config file's table was checked when it was read; Create checks it again.
    Result<idle::IdlePolicy> policy = idle::IdlePolicy::Create(*settings_.idle);
    RADFARM_RETURN_IF_ERROR(policy);
    idle::IdleSources sources = idle::SystemIdleSources();
    if (!settings_.idle_source.empty()) {
      LogLine(LogLevel::kInfo, "agent")
          << "reading the user's activity from " << settings_.idle_source << " (--idle-source)";
      sources.user = std::make_unique<FileUserIdle>(settings_.idle_source);
    }
    idle_monitor_ = std::make_unique<idle::IdleMonitor>(
        loop_, std::move(policy).value(), std::move(sources),
        [this](const idle::IdleDecision& decision) { OnIdleChange(decision); });
    // Nothing is taken before the policy's first answer, about a second from now.
    may_work_ = false;
    state_ = State::kPaused;
    waiting_reason_ = idle_monitor_->decision().reason;
    idle_monitor_->Start();
  } else {
    StartAttempt();
  }
  UpdateIdleTimer();  // --exit-when-idle counts from the start, connected or not
  if (systemd_ != nullptr) systemd_->Ready();
  ReportStatus();
  return Ok{};
}

void Agent::StartAttempt() {
  state_ = State::kConnecting;
  ++attempt_;
  LogLine(LogLevel::kDebug, "agent")
      << "connecting to " << master_ << " (attempt " << attempt_ << ")";
  ReportStatus();
  if (!settings_.master_file.empty()) {
    ConnectFromMasterFile();
    return;
  }
  if (Result<loop::SocketAddress> literal = loop::SocketAddress::FromIpLiteral(settings_.master)) {
    Connect(*literal);
    return;
  }
  // A host name: getaddrinfo blocks, so it runs on the I/O worker.
  Status submitted = io_->Submit(
      [master = settings_.master, n = attempt_ - 1] { return ResolveMaster(master, n); },
      [this](Result<loop::SocketAddress> address) {
        --resolving_;
        if (state_ != State::kConnecting || link_) return;
        if (!address) {
          ScheduleRetry("cannot connect to", address.error());
          return;
        }
        Connect(*address);
      });
  if (submitted) {
    ++resolving_;
  } else {
    ScheduleRetry("cannot connect to", submitted.error());
  }
}

// The file is read again at every attempt: it does not exist before the master listens, and a
// master restarted on port 0 writes another port into it. Reading and resolving both block, so
// they run on the I/O worker.
void Agent::ConnectFromMasterFile() {
  struct Found {
    loop::HostPort master;
    loop::SocketAddress address;
  };
  Status submitted = io_->Submit(
      [file = settings_.master_file, n = attempt_ - 1]() -> Result<Found> {
        Result<loop::HostPort> master = ReadMasterFile(file);
        RADFARM_RETURN_IF_ERROR(master);
        Result<loop::SocketAddress> address = loop::SocketAddress::FromIpLiteral(*master);
        if (!address) address = ResolveMaster(*master, n);
        RADFARM_RETURN_IF_ERROR(address);
        return Found{*master, *address};
      },
      [this](Result<Found> found) {
        --resolving_;
        if (state_ != State::kConnecting || link_) return;
        if (!found) {
          ScheduleRetry("cannot connect to", found.error());
          return;
        }
        const std::string master = found->master.ToString();
        if (master != master_) {
          LogLine(LogLevel::kInfo, "agent") << settings_.master_file << " names " << master;
          master_ = master;
        }
        Connect(found->address);
      });
  if (submitted) {
    ++resolving_;
  } else {
    ScheduleRetry("cannot connect to", submitted.error());
  }
}

void Agent::Connect(const loop::SocketAddress& address) {
  protocol::AgentConfig config;
  config.name = settings_.name;
  config.threads = settings_.threads;
  MasterLink::Timing timing;
  timing.handshake_timeout = kHandshakeTimeout;
  timing.flush_timeout = kFlushTimeout;
  MasterLink::Callbacks callbacks;
  callbacks.on_authenticated = [this](const protocol::WelcomeMsg& w) { OnAuthenticated(w); };
  callbacks.on_message = [this](const protocol::Message& m) { OnMessage(m); };
  callbacks.on_closed = [this](const LinkClosed& closed) { OnLinkClosed(closed); };
  Result<std::unique_ptr<MasterLink>> link =
      MasterLink::Connect(loop_, address, secret_, config, timing, std::move(callbacks));
  if (!link) {
    ScheduleRetry("cannot connect to", link.error());
    return;
  }
  link_ = std::move(link).value();
}

void Agent::OnAuthenticated(const protocol::WelcomeMsg& welcome) {
  state_ = State::kConnected;
  // The backoff starts over only once the master sends something after its Welcome (OnMessage):
  // a master refuses agents right after the handshake, so a Welcome alone is no success, and a
  // refused agent must ask less and less often.
  draining_ = false;
  LogLine(LogLevel::kInfo, "agent") << "connected to " << master_ << " as " << settings_.name
                                    << " (agent id " << welcome.agent_id << ")";
  const milliseconds interval(welcome.heartbeat_interval_ms);
  heartbeat_timer_->Start(interval, interval, [this] { SendHeartbeat(); });
  SendHeartbeat();
  UpdateIdleTimer();
  ReportStatus();
}

void Agent::OnMessage(const protocol::Message& message) {
  if (state_ != State::kConnected) return;  // stopping: the work messages no longer matter
  if (attempt_ > 0) {  // the first message since the Welcome: this connection is a success
    attempt_ = 0;
    backoff_.Reset();
  }
  if (const auto* lease = std::get_if<protocol::LeaseAssignmentMsg>(&message)) {
    runner_->OnLease(*lease, !draining_);
    UpdateIdleTimer();
  } else if (const auto* points = std::get_if<protocol::PointLeaseMsg>(&message)) {
    runner_->OnPointLease(*points, !draining_);
    UpdateIdleTimer();
  } else if (const auto* revoke = std::get_if<protocol::LeaseRevokeMsg>(&message)) {
    runner_->Revoke(*revoke);
  } else if (const auto* cancel = std::get_if<protocol::CancelMsg>(&message)) {
    const size_t dropped = runner_->Cancel(cancel->job_id);
    // The master sends Cancel whenever a job stops running there (done, cancelled, paused or
    // failed) and says not which, so the log says only that it ended.
    LogLine(LogLevel::kInfo, "agent") << "job " << cancel->job_id << " ended on " << master_
                                      << ": dropped " << dropped << " leases";
  } else if (const auto* chunk = std::get_if<protocol::SceneChunkMsg>(&message)) {
    runner_->scenes().OnChunk(*chunk);
  } else if (const auto* unavailable = std::get_if<protocol::SceneUnavailableMsg>(&message)) {
    runner_->scenes().OnUnavailable(*unavailable);
  } else if (const auto* drain = std::get_if<protocol::DrainMsg>(&message)) {
    OnDrain(*drain);
  } else if (const auto* heartbeat = std::get_if<protocol::HeartbeatMsg>(&message)) {
    LogLine(LogLevel::kDebug, "agent")
        << "heartbeat from " << master_ << ": it records " << heartbeat->leases_held
        << " leases of ours, we hold " << runner_->held();
  }
}

void Agent::OnDrain(const protocol::DrainMsg& drain) {
  const bool finish = drain.mode == protocol::DrainMode::kFinishLeases;
  LogLine(LogLevel::kInfo, "agent")
      << "drain from " << master_ << ": " << (finish ? "finishing" : "returning") << " "
      << runner_->held() << " leases" << (drain.exit_after ? ", then exiting" : "");
  draining_ = true;
  exit_when_drained_ = exit_when_drained_ || drain.exit_after;
  if (!finish) runner_->ReturnAll(protocol::LeaseReturnReason::kDraining, "drain from the master");
  OnLeasesChanged();
}

void Agent::OnLeasesChanged() {
  if (state_ == State::kConnected && draining_ && exit_when_drained_ && runner_->held() == 0) {
    Finish("drained, as the master asked");
    return;
  }
  UpdateIdleTimer();
}

void Agent::OnLinkClosed(const LinkClosed& closed) {
  std::unique_ptr<MasterLink> dead = std::move(link_);  // allowed: on_closed is its last act
  heartbeat_timer_->Stop();
  if (state_ == State::kStopping) {
    StopLoop();
    return;
  }
  const size_t dropped = runner_->DropAll();
  if (exit_when_drained_) {  // nothing is held any more: drained
    state_ = State::kWaiting;
    Finish("the connection closed while draining before exit");
    return;
  }
  if (state_ == State::kPaused || !may_work_) {
    // Our own disconnect after a pause, or the master went away while we were pausing.
    state_ = State::kPaused;
    LogLine(LogLevel::kDebug, "agent") << "disconnected from " << master_ << " while paused";
    if (may_work_) Resume("idle again while disconnecting");
    UpdateIdleTimer();
    ReportStatus();
    return;
  }
  state_ = State::kWaiting;
  if (closed.blocklisted) {
    // Our results failed the master's validation: coming straight back would only be refused
    // work again. Say why, loudly, and wait long enough for an operator to look.
    ScheduleRetry("blocklisted by",
                  closed.reason +
                      " (this agent's results failed validation: check its hardware "
                      "and that it runs the master's radfarm release)",
                  kBlocklistedRetry);
  } else if (closed.refused) {
    // Full, or this name has its connections: the backoff grows, so a refused agent asks less
    // and less often, and says why at each step.
    ScheduleRetry("refused by", closed.reason);
  } else if (closed.was_authenticated && closed.auth_failed) {
    // `radfarm agents revoke`: our key is no good any more; retrying is refused at the handshake
    // until an operator enrolls this agent again and gives it the new key.
    ScheduleRetry("authentication with",
                  "revoked: " + closed.reason + "; dropped " + std::to_string(dropped) + " leases");
  } else if (closed.was_authenticated) {
    ScheduleRetry("lost the connection to",
                  closed.reason + "; dropped " + std::to_string(dropped) + " leases");
  } else if (closed.auth_failed) {
    ScheduleRetry(
        "authentication with",
        "failed: " + closed.reason +
            " (does the agent's secret file hold the farm secret, or this agent's key from "
            "`radfarm agents enroll`?)");
  } else {
    ScheduleRetry("cannot connect to", closed.reason);
  }
}

void Agent::ScheduleRetry(const std::string& what, const std::string& reason,
                          milliseconds at_least) {
  state_ = State::kWaiting;
  const milliseconds delay = std::max(backoff_.Next(), at_least);
  const LogLevel level = what == "authentication with" || what == "blocklisted by"
                             ? LogLevel::kError
                             : LogLevel::kWarning;
  // attempt_ is 0 when an established connection was lost: no attempt failed.
  const std::string attempt =
      attempt_ > 0 ? " (attempt " + std::to_string(attempt_) + ")" : std::string();
  LogLine(level, "agent") << what << " " << master_ << attempt << ": " << reason << "; retrying in "
                          << delay.count() << " ms";
  waiting_reason_ = what + " " + master_ + ": " + reason;
  retry_timer_->Start(delay, [this] { StartAttempt(); });
  UpdateIdleTimer();
  ReportStatus();
}

void Agent::OnIdleChange(const idle::IdleDecision& decision) {
  may_work_ = decision.may_work;
  if (decision.may_work) {
    Resume(decision.reason);
  } else {
    Pause(decision.reason);
  }
}

void Agent::Pause(const std::string& reason) {
  waiting_reason_ = reason;
  switch (state_) {
    case State::kStopping:
      return;
    case State::kPaused:
      // Still paused (the first answer, or busy again while our disconnect is flushing).
      LogLine(LogLevel::kInfo, "agent") << "waiting: " << reason;
      ReportStatus();
      return;
    case State::kWaiting:
      retry_timer_->Stop();
      LogLine(LogLevel::kInfo, "agent")
          << "pausing: " << reason << "; not connecting to " << master_ << " until idle again";
      break;
    case State::kConnecting:
      // A name lookup still running finds state_ changed and drops its answer; a handshake in
      // progress is abandoned (destroying the link closes it silently).
      link_.reset();
      LogLine(LogLevel::kInfo, "agent")
          << "pausing: " << reason << "; gave up connecting to " << master_ << " until idle again";
      break;
    case State::kConnected: {
      const size_t held = runner_->held();
      LogLine(LogLevel::kInfo, "agent")
          << "pausing: " << reason << "; returning " << held << " leases to " << master_
          << " and disconnecting until idle again";
      state_ = State::kPaused;
      heartbeat_timer_->Stop();
      // Every lease, queued or running, goes back now: the master requeues them at once. Then
      // the connection ends, so the master leases us nothing while we are paused. It ends
      // without a Close message; either way radfarmd requeues at once what the connection still
      // held when it ended (AgentConnections::OnAgentClosed), such as leases sent before it read
      // the LeaseReturn.
      runner_->ReturnAll(protocol::LeaseReturnReason::kOverloaded, "paused: " + reason);
      link_->Disconnect("paused by the idle policy: " + reason);
      break;
    }
  }
  state_ = State::kPaused;
  UpdateIdleTimer();
  ReportStatus();
}

void Agent::Resume(const std::string& reason) {
  if (state_ != State::kPaused) return;
  if (link_) {
    // Our disconnect is still flushing: OnLinkClosed resumes.
    LogLine(LogLevel::kDebug, "agent") << "idle again before the connection closed";
    return;
  }
  LogLine(LogLevel::kInfo, "agent")
      << (ever_worked_ ? "resuming: " : "may work: ") << reason << "; connecting to " << master_;
  ever_worked_ = true;
  waiting_reason_.clear();
  backoff_.Reset();
  attempt_ = 0;
  StartAttempt();
}

void Agent::ReportStatus() {
  if (systemd_ == nullptr) return;
  std::ostringstream text;
  switch (state_) {
    case State::kConnected:
      text << "connected to " << master_ << ", " << runner_->held() << " leases, "
           << static_cast<uint64_t>(runner_->RaysPerSecond()) << " rays/s";
      break;
    case State::kConnecting:
      text << "connecting to " << master_ << " (attempt " << attempt_ << ")";
      break;
    case State::kWaiting:
      text << "waiting: " << waiting_reason_;
      break;
    case State::kPaused:
      text << "waiting: " << waiting_reason_;
      break;
    case State::kStopping:
      text << "stopping";
      break;
  }
  systemd_->Status(text.str());
}

void Agent::SendHeartbeat() {
  protocol::HeartbeatMsg heartbeat;
  heartbeat.load = LoadAverage();
  heartbeat.rays_per_second = runner_->RaysPerSecond();
  heartbeat.leases_held = static_cast<uint32_t>(runner_->held());
  if (Status sent = Send(heartbeat); !sent) {
    LogLine(LogLevel::kDebug, "agent") << "heartbeat not sent: " << sent.error();
  }
  ReportStatus();
}

// --exit-when-idle counts the time without a lease, whatever the reason: connected with no work,
// the master unreachable (a batch agent must not hold its allocation until the walltime because
// the master is gone), or paused by the idle policy. One period runs across reconnects; only a
// lease stops it.
void Agent::UpdateIdleTimer() {
  if (settings_.exit_when_idle_seconds <= 0 || state_ == State::kStopping) return;
  if (state_ == State::kConnected && runner_->held() > 0) {
    idle_timer_->Stop();
    return;
  }
  if (idle_timer_->active()) return;
  const auto idle =
      milliseconds(static_cast<int64_t>(std::min(settings_.exit_when_idle_seconds * 1000, 1e15)));
  idle_timer_->Start(idle, [this] { OnIdleTimeout(); });
}

void Agent::OnIdleTimeout() {
  std::ostringstream reason;
  reason << "no lease for " << settings_.exit_when_idle_seconds << " s";
  if (state_ != State::kConnected) {
    reason << " (" << (waiting_reason_.empty() ? "not connected to " + master_ : waiting_reason_)
           << ")";
  }
  reason << ", as --exit-when-idle asked";
  Finish(reason.str());
}

Status Agent::Send(const protocol::Message& message) {
  if (!link_ || !link_->authenticated()) return Error{"not connected to " + master_};
  return link_->Send(message);
}

void Agent::Finish(const std::string& reason) {
  if (state_ == State::kStopping) return;
  const bool connected = state_ == State::kConnected && link_;
  state_ = State::kStopping;
  if (idle_monitor_) idle_monitor_->Stop();
  if (systemd_ != nullptr) {
    systemd_->Status("stopping: " + reason);
    systemd_->Stopping();
  }
  if (connected) {
    LogLine(LogLevel::kInfo, "agent") << "shutting down: " << reason << "; returning "
                                      << runner_->held() << " leases to " << master_;
  } else {
    LogLine(LogLevel::kInfo, "agent")
        << "shutting down: " << reason << "; not connected to " << master_;
  }
  retry_timer_->Stop();
  heartbeat_timer_->Stop();
  idle_timer_->Stop();
  if (!connected) {
    // Paused, waiting or connecting (or a pause's Close still being flushed).
    runner_->DropAll();
    link_.reset();
    StopLoop();
    return;
  }
  runner_->ReturnAll(protocol::LeaseReturnReason::kDraining, reason);
  link_->Close(protocol::CloseCode::kShutdown, CloseDetail(reason));
  stop_deadline_->Start(kStopDeadline, [this] { StopLoop(); });
}

void Agent::StopLoop() {
  retry_timer_->Stop();
  heartbeat_timer_->Stop();
  idle_timer_->Stop();
  stop_deadline_->Stop();
  loop_.Stop();
}

}  // namespace radfarm::agent
