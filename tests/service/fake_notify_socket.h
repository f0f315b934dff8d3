// FakeNotifySocket: plays systemd's side of sd_notify(3) for a test. It binds a datagram Unix
// socket and points NOTIFY_SOCKET (and, when asked, WATCHDOG_USEC/WATCHDOG_PID) of this process
// at it; the destructor closes it, removes it and restores the variables.
#pragma once

#include <chrono>
#include <optional>
#include <string>
#include <vector>

namespace radfarm::service::testing {

class FakeNotifySocket {
 public:
  // `watchdog`: the WATCHDOG_USEC to advertise, with WATCHDOG_PID = `watchdog_pid` (0: ours).
  explicit FakeNotifySocket(std::optional<std::chrono::microseconds> watchdog = std::nullopt,
                            int watchdog_pid = 0);
  ~FakeNotifySocket();
  FakeNotifySocket(const FakeNotifySocket&) = delete;
  FakeNotifySocket& operator=(const FakeNotifySocket&) = delete;

  bool ok() const { return fd_ >= 0; }
  // Every datagram received so far, split into its lines ("READY=1", "STATUS=..."), appended to
  // what earlier calls returned. Does not block.
  const std::vector<std::string>& Lines();
  size_t Count(const std::string& line);

 private:
  int fd_ = -1;
  std::string path_;
  std::vector<std::string> lines_;
};

}  // namespace radfarm::service::testing
