#include "service/service_notifier.h"

#include <systemd/sd-daemon.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>

#include "loop/log.h"

namespace radfarm::service {
namespace {

constexpr std::string_view kComponent = "systemd";

}  // namespace

std::string OneLine(std::string_view text) {
  std::string line(text);
  for (char& c : line) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte < 0x20 || byte == 0x7f) c = ' ';
  }
  return line;
}

ServiceNotifier::ServiceNotifier(loop::EventLoop& loop) {
  const char* socket = std::getenv("NOTIFY_SOCKET");
  enabled_ = socket != nullptr && socket[0] != '\0';
  if (!enabled_) return;

  uint64_t usec = 0;
  const int watchdog = sd_watchdog_enabled(/*unset_environment=*/0, &usec);
  if (watchdog < 0) {
    loop::LogLine(loop::LogLevel::kWarning, kComponent)
        << "watchdog off: WATCHDOG_USEC/WATCHDOG_PID unreadable: " << std::strerror(-watchdog);
    return;
  }
  if (watchdog == 0) return;  // no WatchdogSec=, or the variables name another process

  feed_interval_ = std::chrono::microseconds(usec / 2);
  const auto period =
      std::max(std::chrono::milliseconds(1),
               std::chrono::duration_cast<std::chrono::milliseconds>(*feed_interval_));
  watchdog_timer_ = std::make_unique<loop::Timer>(loop);
  watchdog_timer_->Start(std::chrono::milliseconds(0), period, [this] { Send("WATCHDOG=1"); });
  loop::LogLine(loop::LogLevel::kInfo, kComponent)
      << "watchdog on: feeding every " << period.count() << " ms";
}

ServiceNotifier::~ServiceNotifier() = default;

void ServiceNotifier::Ready() { Send("READY=1"); }

void ServiceNotifier::Status(std::string_view text) {
  std::string line = OneLine(text);
  if (last_status_ == line) return;
  last_status_ = line;
  Send("STATUS=" + line);
}

void ServiceNotifier::Stopping() {
  if (watchdog_timer_) watchdog_timer_->Stop();
  Send("STOPPING=1");
}

void ServiceNotifier::Send(const std::string& message) {
  if (!enabled_) return;
  const int sent = sd_notify(/*unset_environment=*/0, message.c_str());
  if (sent >= 0 || send_failure_logged_) return;
  send_failure_logged_ = true;
  loop::LogLine(loop::LogLevel::kWarning, kComponent)
      << "cannot notify systemd (further failures are not logged): " << std::strerror(-sent);
}

}  // namespace radfarm::service
