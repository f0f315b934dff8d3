#include "idle/idle_monitor.h"

#include "idle/logind_user_idle.h"
#include "loop/log.h"

namespace radfarm::idle {

IdleSources SystemIdleSources() {
  return IdleSources{std::make_unique<LogindUserIdle>(), std::make_unique<ProcCpuLoad>(),
                     LocalTimeNow};
}

IdleMonitor::IdleMonitor(loop::EventLoop& loop, IdlePolicy policy, IdleSources sources,
                         OnChange on_change, IdleMonitorTiming timing)
    : loop_(loop),
      policy_(std::move(policy)),
      sources_(std::move(sources)),
      on_change_(std::move(on_change)),
      timing_(timing),
      timer_(std::make_unique<loop::Timer>(loop)) {}

IdleMonitor::~IdleMonitor() = default;

void IdleMonitor::Start() {
  other_cpu_ = sources_.cpu->OtherLoad();  // the baseline; null the first time
  cpu_measured_ = other_cpu_.has_value();
  next_cpu_read_ms_ = loop_.NowMs() + static_cast<uint64_t>(timing_.first_cpu_window.count());
  timer_->Start(timing_.check_interval, timing_.check_interval, [this] { Check(); });
}

void IdleMonitor::Stop() { timer_->Stop(); }

void IdleMonitor::Check() {
  const uint64_t now_ms = loop_.NowMs();
  if (now_ms >= next_cpu_read_ms_) {
    other_cpu_ = sources_.cpu->OtherLoad();
    // An unreadable load stays unknown (the policy logs it) rather than holding the agent back.
    cpu_measured_ = true;
    next_cpu_read_ms_ = now_ms + static_cast<uint64_t>(policy_.config().poll_seconds) * 1000;
  }
  if (!cpu_measured_) return;

  const IdleSample sample{std::chrono::steady_clock::time_point(std::chrono::milliseconds(now_ms)),
                          sources_.user->Read(), other_cpu_, sources_.local_time()};
  IdleDecision decision = policy_.Decide(sample);
  const bool changed = !decided_ || decision.may_work != decision_.may_work;
  decided_ = true;
  decision_ = std::move(decision);
  if (!changed) return;
  loop::LogLine(loop::LogLevel::kInfo, "idle")
      << (decision_.may_work ? "taking work: " : "not taking work: ") << decision_.reason;
  on_change_(decision_);
}

}  // namespace radfarm::idle
