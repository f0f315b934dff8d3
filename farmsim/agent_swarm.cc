#include "farmsim/agent_swarm.h"

#include <time.h>

#include <algorithm>
#include <stdexcept>

#include "loop/event_loop.h"
#include "loop/host_port.h"
#include "loop/socket_address.h"
#include "loop/timer.h"

namespace radfarm::sim {
namespace {

// Agents connect in groups, so the master's listen backlog never overflows.
constexpr size_t kConnectGroup = 50;
constexpr double kConnectGroupSeconds = 0.005;
// After the first Cancel, how long the others get to arrive before the connections close.
constexpr double kEndGraceSeconds = 0.3;
constexpr double kCloseWaitSeconds = 3;

double ThreadCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

loop::SocketAddress ParseAddress(const std::string& text) {
  Result<loop::HostPort> host_port = loop::ParseHostPort(text, "master address");
  if (!host_port) throw std::runtime_error(host_port.error());
  Result<loop::SocketAddress> address = loop::SocketAddress::FromIpLiteral(*host_port);
  if (!address) throw std::runtime_error(address.error());
  return *address;
}

}  // namespace

AgentSwarm::AgentSwarm(SwarmConfig config)
    : config_(std::move(config)), master_(ParseAddress(config_.master_address)) {}

AgentSwarm::~AgentSwarm() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  if (thread_.joinable()) thread_.join();
}

void AgentSwarm::Start(std::chrono::seconds timeout) {
  thread_ = std::thread([this] { Run(); });
  std::unique_lock lock(mutex_);
  const bool up = changed_.wait_for(lock, timeout, [&] {
    return authenticated_ == config_.agents || !failure_.empty() || finished_;
  });
  if (!failure_.empty()) throw std::runtime_error(failure_);
  if (!up || authenticated_ < config_.agents) {
    throw std::runtime_error(std::to_string(authenticated_) + " of " +
                             std::to_string(config_.agents) + " simulated agents authenticated");
  }
}

SwarmReport AgentSwarm::Finish(std::chrono::seconds timeout) {
  std::unique_lock lock(mutex_);
  const bool done = changed_.wait_for(lock, timeout, [&] { return finished_; });
  if (!done) {
    stop_ = true;
    changed_.wait(lock, [&] { return finished_; });
  }
  if (!failure_.empty()) throw std::runtime_error(failure_);
  if (!ended_) {
    throw std::runtime_error("the job did not end within " + std::to_string(timeout.count()) +
                             " s");
  }
  return report_;
}

void AgentSwarm::OnAuthenticated() {
  std::lock_guard lock(mutex_);
  ++authenticated_;
  changed_.notify_all();
}

void AgentSwarm::OnCancel(uint64_t /*job_id*/, double arrival) {
  std::lock_guard lock(mutex_);
  if (report_.job_end < 0 || arrival < report_.job_end) report_.job_end = arrival;
  ended_ = true;
}

bool AgentSwarm::SceneVerified(const protocol::SceneHash& hash) const {
  return verified_scenes_.count(hash) > 0;
}

void AgentSwarm::OnSceneVerified(const protocol::SceneHash& hash) { verified_scenes_.insert(hash); }

void AgentSwarm::OnAgentClosed(const std::string& name, const std::string& reason) {
  std::lock_guard lock(mutex_);
  if (ended_) return;  // closing at the end is expected
  report_.errors.push_back(name + ": " + reason);
  if (authenticated_ < config_.agents && failure_.empty()) {
    failure_ = "simulated agent " + name + " closed before the job: " + reason;
    changed_.notify_all();
  }
}

void AgentSwarm::Run() {
  const double cpu_start = ThreadCpuSeconds();
  Result<protocol::FarmSecret> secret = protocol::FarmSecret::FromHex(config_.secret_hex);
  loop::EventLoop loop;
  auto delays = std::make_unique<DelayLine>(loop);
  std::vector<std::unique_ptr<SimAgent>> agents;
  auto heartbeat = std::make_unique<loop::Timer>(loop);
  auto poll = std::make_unique<loop::Timer>(loop);
  const double connect_start = SteadySeconds();
  double shutdown_at = -1;

  const auto fail = [&](const std::string& why) {
    std::lock_guard lock(mutex_);
    if (failure_.empty()) failure_ = why;
    changed_.notify_all();
  };
  if (!secret) {
    fail("bad farm secret: " + secret.error());
  } else {
    for (size_t i = 0; i < config_.agents; ++i) {
      SwarmHooks& hooks = *this;
      agents.push_back(std::make_unique<SimAgent>(loop, *delays, master_, *secret, config_.agent,
                                                  config_.name_prefix + std::to_string(i), hooks));
    }
    for (size_t first = 0; first < agents.size(); first += kConnectGroup) {
      delays->At(connect_start + kConnectGroupSeconds * double(first / kConnectGroup), [&, first] {
        for (size_t i = first; i < std::min(agents.size(), first + kConnectGroup); ++i) {
          if (Status s = agents[i]->Connect(); !s) fail(s.error());
        }
      });
    }
    heartbeat->Start(std::chrono::milliseconds(config_.heartbeat_ms),
                     std::chrono::milliseconds(config_.heartbeat_ms), [&] {
                       for (auto& agent : agents) agent->SendHeartbeat();
                     });
    bool connected = false;
    poll->Start(std::chrono::milliseconds(5), std::chrono::milliseconds(5), [&] {
      std::unique_lock lock(mutex_);
      if (!connected && authenticated_ == config_.agents) {
        connected = true;
        report_.connect_seconds = SteadySeconds() - connect_start;
      }
      const bool give_up = stop_ || !failure_.empty();
      const bool over = ended_ && SteadySeconds() > report_.job_end + kEndGraceSeconds +
                                                        2 * config_.agent.latency_seconds;
      lock.unlock();
      if (shutdown_at < 0 && (give_up || over)) {
        shutdown_at = SteadySeconds();
        for (auto& agent : agents) agent->Shutdown();
      }
      if (shutdown_at >= 0) {
        const bool all_closed =
            std::none_of(agents.begin(), agents.end(), [](const auto& a) { return a->open(); });
        if (all_closed || SteadySeconds() > shutdown_at + kCloseWaitSeconds) loop.Stop();
      }
    });
    loop.Run();
  }

  SwarmReport report;
  for (const auto& agent : agents) {
    const SimAgentStats& s = agent->stats();
    report.agents.push_back(s);
    for (const auto& [number, span] : s.rounds) {
      RoundSpan& merged = report.rounds[number];
      if (merged.first_assignment < 0 || span.first_assignment < merged.first_assignment) {
        merged.first_assignment = span.first_assignment;
      }
      merged.last_result = std::max(merged.last_result, span.last_result);
      merged.busy_seconds += span.busy_seconds;
      merged.batches += span.batches;
    }
    if (s.first_assignment >= 0 &&
        (report.job_start < 0 || s.first_assignment < report.job_start)) {
      report.job_start = s.first_assignment;
    }
  }
  report.mean_lateness = delays->mean_lateness();
  report.max_lateness = delays->max_lateness();
  heartbeat.reset();
  poll.reset();
  delays->Close();
  agents.clear();
  delays.reset();
  const Status closed = loop.Close();
  std::lock_guard lock(mutex_);
  if (!closed && failure_.empty()) failure_ = "the swarm's loop did not close: " + closed.error();
  report.connect_seconds = report_.connect_seconds;
  report.job_end = report_.job_end;
  report.errors = report_.errors;
  report.cpu_seconds = ThreadCpuSeconds() - cpu_start;
  report_ = std::move(report);
  finished_ = true;
  changed_.notify_all();
}

}  // namespace radfarm::sim
