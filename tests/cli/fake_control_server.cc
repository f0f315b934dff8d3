#include "tests/cli/fake_control_server.h"

#include <fcntl.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <cstring>
#include <stdexcept>

namespace radfarm::testing {
namespace {

void SendAll(int fd, const std::string& bytes) {
  size_t at = 0;
  while (at < bytes.size()) {
    const ssize_t n = ::send(fd, bytes.data() + at, bytes.size() - at, MSG_NOSIGNAL);
    if (n <= 0) return;  // the client went away; the test looks at what it printed
    at += size_t(n);
  }
}

}  // namespace

ControlAnswer OkAnswer(nlohmann::json fields) {
  fields["ok"] = true;
  return ControlAnswer{fields, {}, std::nullopt, false};
}

ControlAnswer ErrorAnswer(const std::string& code, const std::string& message) {
  return ControlAnswer{
      {{"ok", false}, {"error", message}, {"code", code}}, {}, std::nullopt, false};
}

FakeControlServer::Handler Always(ControlAnswer answer) {
  return [answer](const ControlRequest&) { return answer; };
}

std::string Frame(const std::string& payload) {
  const uint32_t n = uint32_t(payload.size());
  std::string frame = {char(n & 0xff), char(n >> 8 & 0xff), char(n >> 16 & 0xff),
                       char(n >> 24 & 0xff)};
  return frame + payload;
}

UnixListener::UnixListener(const TempDir& dir, bool listen) : path_(dir.File("control.sock")) {
  fd_ = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  if (fd_ < 0 || path_.size() >= sizeof address.sun_path) throw std::runtime_error("socket");
  std::memcpy(address.sun_path, path_.c_str(), path_.size());
  if (::bind(fd_, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0 ||
      (listen && ::listen(fd_, 8) != 0)) {
    throw std::runtime_error(path_ + ": " + std::strerror(errno));
  }
}

UnixListener::~UnixListener() {
  if (fd_ >= 0) ::close(fd_);
}

bool UnixListener::HasPendingConnection() const {
  pollfd p{fd_, POLLIN, 0};
  return ::poll(&p, 1, 0) == 1;
}

FakeControlServer::FakeControlServer(Handler handler)
    : listener_(dir_), handler_(std::move(handler)) {
  if (::pipe2(wake_, O_CLOEXEC) != 0) throw std::runtime_error("pipe2");
  thread_ = std::thread([this] { Serve(); });
}

FakeControlServer::~FakeControlServer() {
  const char stop = 's';
  (void)!::write(wake_[1], &stop, 1);
  thread_.join();
  ::close(wake_[0]);
  ::close(wake_[1]);
}

std::vector<ControlRequest> FakeControlServer::requests() const {
  std::lock_guard lock(mutex_);
  return requests_;
}

int FakeControlServer::connections() const {
  std::lock_guard lock(mutex_);
  return connections_;
}

void FakeControlServer::Serve() {
  for (;;) {
    pollfd fds[2] = {{listener_.fd(), POLLIN, 0}, {wake_[0], POLLIN, 0}};
    if (::poll(fds, 2, -1) < 0) continue;
    if (fds[1].revents != 0) return;
    const int fd = ::accept4(listener_.fd(), nullptr, nullptr, SOCK_CLOEXEC);
    if (fd < 0) continue;
    {
      std::lock_guard lock(mutex_);
      ++connections_;
    }
    ServeConnection(fd);
    ::close(fd);
  }
}

void FakeControlServer::ServeConnection(int fd) {
  for (;;) {
    std::vector<uint8_t> frame;
    if (!ReadFrame(fd, &frame)) return;
    ControlRequest request;
    request.body = nlohmann::json::parse(frame.begin(), frame.end(), nullptr, false);
    if (request.body.is_object() && request.body.contains("attachment_bytes") &&
        !ReadFrame(fd, &request.attachment)) {
      return;
    }
    {
      std::lock_guard lock(mutex_);
      requests_.push_back(request);
    }
    ControlAnswer answer = handler_(request);
    if (answer.raw) {
      SendAll(fd, *answer.raw);
    } else if (!answer.close || !answer.body.is_null()) {
      if (!answer.attachment.empty()) answer.body["attachment_bytes"] = answer.attachment.size();
      SendAll(fd, Frame(answer.body.dump()));
      if (!answer.attachment.empty()) {
        SendAll(fd, Frame(std::string(answer.attachment.begin(), answer.attachment.end())));
      }
    }
    if (answer.close) return;
  }
}

bool FakeControlServer::ReadExact(int fd, uint8_t* data, size_t size) {
  while (size > 0) {
    pollfd fds[2] = {{fd, POLLIN, 0}, {wake_[0], POLLIN, 0}};
    if (::poll(fds, 2, -1) < 0) continue;
    if (fds[1].revents != 0) return false;
    const ssize_t n = ::recv(fd, data, size, 0);
    if (n <= 0) return false;
    data += n;
    size -= size_t(n);
  }
  return true;
}

bool FakeControlServer::ReadFrame(int fd, std::vector<uint8_t>* payload) {
  uint8_t prefix[4];
  if (!ReadExact(fd, prefix, 4)) return false;
  const uint32_t n = uint32_t(prefix[0]) | uint32_t(prefix[1]) << 8 | uint32_t(prefix[2]) << 16 |
                     uint32_t(prefix[3]) << 24;
  payload->resize(n);
  return ReadExact(fd, payload->data(), n);
}

}  // namespace radfarm::testing
