// IdleMonitor: runs an IdlePolicy on the agent's event loop. A timer reads the user's idle state
// and the local time every `check_interval` (500 ms: a returning user stops the agent within a
// second) and the other processes' CPU load every poll_seconds; `on_change` runs when the answer
// to "may this agent take work?" changes, and once for the first answer.
//
// The agent's side of the contract: when on_change says no, stop asking for batches and hand back
// every lease at once; when it says yes again, ask again.
//
// Loop thread only; the sources are read on the loop thread (LogindUserIdle bounds its D-Bus call
// to 250 ms). Construct after the EventLoop, destroy before it.
#pragma once

#include <chrono>
#include <functional>
#include <memory>
#include <optional>

#include "idle/cpu_load.h"
#include "idle/idle_policy.h"
#include "idle/local_time.h"
#include "idle/user_idle.h"
#include "loop/event_loop.h"
#include "loop/timer.h"

namespace radfarm::idle {

struct IdleSources {
  std::unique_ptr<UserIdleSource> user;
  std::unique_ptr<CpuLoadSource> cpu;
  std::function<LocalTime()> local_time;
};
// logind, /proc/stat + getrusage, the local clock.
IdleSources SystemIdleSources();

struct IdleMonitorTiming {
  std::chrono::milliseconds check_interval{500};
  // The first CPU measurement covers this long (later ones poll_seconds), so the first answer
  // comes soon after Start().
  std::chrono::milliseconds first_cpu_window{1000};
};

class IdleMonitor {
 public:
  using OnChange = std::function<void(const IdleDecision& decision)>;

  IdleMonitor(loop::EventLoop& loop, IdlePolicy policy, IdleSources sources, OnChange on_change,
              IdleMonitorTiming timing = {});
  ~IdleMonitor();
  IdleMonitor(const IdleMonitor&) = delete;
  IdleMonitor& operator=(const IdleMonitor&) = delete;

  // Takes the CPU baseline and starts the timer. Until the first answer, may_work() is false.
  void Start();
  void Stop();

  bool may_work() const { return decision_.may_work; }
  // The latest decision, with its reason (for STATUS= lines and the agent's log).
  const IdleDecision& decision() const { return decision_; }

 private:
  void Check();

  loop::EventLoop& loop_;
  IdlePolicy policy_;
  IdleSources sources_;
  OnChange on_change_;
  IdleMonitorTiming timing_;
  std::unique_ptr<loop::Timer> timer_;

  std::optional<double> other_cpu_;
  uint64_t next_cpu_read_ms_ = 0;
  bool cpu_measured_ = false;
  bool decided_ = false;
  IdleDecision decision_{false, "measuring the CPU load"};
};

}  // namespace radfarm::idle
