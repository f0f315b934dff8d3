// ServiceNotifier: tells systemd (Type=notify units) how a daemon is doing, through sd_notify(3).
//
//   READY=1      Ready():    once the store is open and the listener bound
//   STATUS=...   Status():   a one-line summary ("3 jobs, 12 agents"); repeats are not resent
//   STOPPING=1   Stopping(): at the start of an orderly shutdown
//   WATCHDOG=1   by itself, from a loop::Timer at half the unit's WatchdogSec=
//
// The watchdog is fed from the event loop on purpose: a loop that hangs (a callback that never
// returns, a deadlock on the loop thread) stops feeding it and systemd restarts the daemon.
//
// Without systemd (NOTIFY_SOCKET unset, e.g. run from a shell or under HTCondor/Slurm) every call
// is a no-op and no timer runs. A failing send is logged once and otherwise ignored: telling
// systemd is never a reason to stop serving.
//
// Loop thread only; construct it after the EventLoop and destroy it before (it owns a Timer).
#pragma once

#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "loop/event_loop.h"
#include "loop/timer.h"

namespace radfarm::service {

class ServiceNotifier {
 public:
  // Reads NOTIFY_SOCKET, WATCHDOG_USEC and WATCHDOG_PID now; starts feeding the watchdog when it
  // is enabled for this process (the first WATCHDOG=1 goes out on the loop's first iteration).
  explicit ServiceNotifier(loop::EventLoop& loop);
  ~ServiceNotifier();
  ServiceNotifier(const ServiceNotifier&) = delete;
  ServiceNotifier& operator=(const ServiceNotifier&) = delete;

  void Ready();
  // `text` is sent on one line: control characters (a newline could forge READY=1) become spaces.
  void Status(std::string_view text);
  // Also stops feeding the watchdog: the unit's stop timeout (TimeoutStopSec=) takes over.
  void Stopping();

  // Whether NOTIFY_SOCKET was set at construction.
  bool enabled() const { return enabled_; }
  // How often WATCHDOG=1 is sent (half of WATCHDOG_USEC), when the watchdog is on.
  std::optional<std::chrono::microseconds> watchdog_feed_interval() const { return feed_interval_; }

 private:
  void Send(const std::string& message);

  bool enabled_ = false;
  bool send_failure_logged_ = false;
  std::optional<std::chrono::microseconds> feed_interval_;
  std::optional<std::string> last_status_;
  std::unique_ptr<loop::Timer> watchdog_timer_;
};

// The text with every control character replaced by a space, for a STATUS= line.
std::string OneLine(std::string_view text);

}  // namespace radfarm::service
