#include "tests/farm/tamper_proxy.h"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <memory>
#include <vector>

#include "tests/farm/raw_peer.h"

namespace radfarm::testing {
namespace {

// The handshake's frames from the agent: Hello and Proof. Later ones are sealed.
constexpr int kAgentHandshakeFrames = 2;

// One relayed connection. The agent->master bytes are followed frame by frame (length prefixes)
// so that exactly one bit of one chosen frame is flipped.
struct Relay {
  int agent = -1, master = -1;
  bool tamper = false;
  uint8_t prefix[4] = {};
  size_t prefix_bytes = 0;
  uint64_t frame_left = 0;  // body bytes of the current frame still to pass
  int frames = 0;
  bool flip_this_frame = false;
  uint64_t flip_at = 0;  // counts down through the chosen frame's body

  ~Relay() {
    ::close(agent);
    ::close(master);
  }

  // Runs the agent's bytes through the frame tracker; returns whether it flipped a bit.
  bool Track(uint8_t* data, size_t size, uint32_t min_frame_bytes) {
    bool flipped = false;
    for (size_t i = 0; i < size; ++i) {
      if (frame_left == 0) {
        prefix[prefix_bytes++] = data[i];
        if (prefix_bytes < 4) continue;
        prefix_bytes = 0;
        frame_left = uint32_t(prefix[0]) | uint32_t(prefix[1]) << 8 | uint32_t(prefix[2]) << 16 |
                     uint32_t(prefix[3]) << 24;
        flip_this_frame = tamper && frames >= kAgentHandshakeFrames && frame_left > min_frame_bytes;
        flip_at = frame_left / 2;
        ++frames;
        continue;
      }
      if (flip_this_frame && flip_at-- == 0) {
        data[i] ^= 0x04;
        flip_this_frame = false;
        tamper = false;
        flipped = true;
      }
      --frame_left;
    }
    return flipped;
  }
};

bool Forward(int from, int to, std::vector<uint8_t>& buffer, Relay* track, uint32_t min_bytes,
             bool* flipped) {
  const ssize_t n = ::read(from, buffer.data(), buffer.size());
  if (n <= 0) return false;
  if (track != nullptr && track->Track(buffer.data(), size_t(n), min_bytes)) *flipped = true;
  size_t sent = 0;
  while (sent < size_t(n)) {
    const ssize_t w = ::write(to, buffer.data() + sent, size_t(n) - sent);
    if (w <= 0) return false;
    sent += size_t(w);
  }
  return true;
}

}  // namespace

TamperProxy::TamperProxy(std::string target, int tampered_connections, uint32_t min_frame_bytes)
    : target_(std::move(target)),
      tampered_connections_(tampered_connections),
      min_frame_bytes_(min_frame_bytes) {
  listen_fd_ = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  sockaddr_in sa{};
  sa.sin_family = AF_INET;
  sa.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  socklen_t length = sizeof sa;
  if (::bind(listen_fd_, reinterpret_cast<sockaddr*>(&sa), sizeof sa) != 0 ||
      ::listen(listen_fd_, 16) != 0 ||
      ::getsockname(listen_fd_, reinterpret_cast<sockaddr*>(&sa), &length) != 0 ||
      ::pipe2(stop_pipe_, O_CLOEXEC) != 0) {
    return;  // address_ stays empty: the test fails on it
  }
  address_ = "127.0.0.1:" + std::to_string(ntohs(sa.sin_port));
  thread_ = std::thread([this] { Run(); });
}

TamperProxy::~TamperProxy() {
  if (thread_.joinable()) {
    (void)::write(stop_pipe_[1], "x", 1);
    thread_.join();
  }
  ::close(listen_fd_);
  ::close(stop_pipe_[0]);
  ::close(stop_pipe_[1]);
}

void TamperProxy::Run() {
  std::vector<std::unique_ptr<Relay>> relays;
  std::vector<uint8_t> buffer(1 << 16);
  for (;;) {
    std::vector<pollfd> fds = {{stop_pipe_[0], POLLIN, 0}, {listen_fd_, POLLIN, 0}};
    for (const auto& r : relays) {
      fds.push_back({r->agent, POLLIN, 0});
      fds.push_back({r->master, POLLIN, 0});
    }
    if (::poll(fds.data(), fds.size(), -1) < 0) continue;
    if (fds[0].revents != 0) return;
    const size_t polled = relays.size();  // a relay accepted below has no pollfd yet
    if (fds[1].revents & POLLIN) {
      const int agent = ::accept4(listen_fd_, nullptr, nullptr, SOCK_CLOEXEC);
      const int master = agent < 0 ? -1 : ConnectTcpSocket(target_);
      if (agent >= 0 && master < 0) ::close(agent);
      if (agent >= 0 && master >= 0) {
        auto relay = std::make_unique<Relay>();
        relay->agent = agent;
        relay->master = master;
        relay->tamper = connections_.fetch_add(1) < tampered_connections_;
        relays.push_back(std::move(relay));
      }
    }
    for (size_t k = 0; k < polled;) {
      Relay& r = *relays[k];
      const pollfd& from_agent = fds[2 + 2 * k];
      const pollfd& from_master = fds[3 + 2 * k];
      bool open = true, flipped = false;
      if (from_agent.revents != 0) {
        open = Forward(r.agent, r.master, buffer, &r, min_frame_bytes_, &flipped);
      }
      if (open && from_master.revents != 0) {
        open = Forward(r.master, r.agent, buffer, nullptr, 0, &flipped);
      }
      if (flipped) flips_.fetch_add(1);
      if (open) {
        ++k;
        continue;
      }
      // Erasing shifts the relays against their pollfds: stop here and poll again (level
      // triggered, nothing is lost).
      relays.erase(relays.begin() + static_cast<std::ptrdiff_t>(k));
      break;
    }
  }
}

}  // namespace radfarm::testing
