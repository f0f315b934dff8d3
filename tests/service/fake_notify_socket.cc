#include "fake_notify_socket.h"

#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <cstring>
#include <sstream>

namespace radfarm::service::testing {

FakeNotifySocket::FakeNotifySocket(std::optional<std::chrono::microseconds> watchdog,
                                   int watchdog_pid) {
  static std::atomic<int> counter{0};
  path_ = "/tmp/rfn-" + std::to_string(getpid()) + "-" + std::to_string(counter++);
  fd_ = socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
  if (fd_ < 0) return;
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  std::strncpy(address.sun_path, path_.c_str(), sizeof address.sun_path - 1);
  if (bind(fd_, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0) {
    close(fd_);
    fd_ = -1;
    return;
  }
  setenv("NOTIFY_SOCKET", path_.c_str(), 1);
  if (watchdog) {
    setenv("WATCHDOG_USEC", std::to_string(watchdog->count()).c_str(), 1);
    setenv("WATCHDOG_PID", std::to_string(watchdog_pid ? watchdog_pid : getpid()).c_str(), 1);
  }
}

FakeNotifySocket::~FakeNotifySocket() {
  unsetenv("NOTIFY_SOCKET");
  unsetenv("WATCHDOG_USEC");
  unsetenv("WATCHDOG_PID");
  if (fd_ >= 0) {
    close(fd_);
    unlink(path_.c_str());
  }
}

const std::vector<std::string>& FakeNotifySocket::Lines() {
  char buffer[4096];
  for (;;) {
    const ssize_t n = recv(fd_, buffer, sizeof buffer, 0);
    if (n < 0) break;  // EAGAIN: nothing more for now
    std::istringstream datagram(std::string(buffer, static_cast<size_t>(n)));
    for (std::string line; std::getline(datagram, line);) lines_.push_back(line);
  }
  return lines_;
}

size_t FakeNotifySocket::Count(const std::string& line) {
  const auto& lines = Lines();
  return static_cast<size_t>(std::count(lines.begin(), lines.end(), line));
}

}  // namespace radfarm::service::testing
