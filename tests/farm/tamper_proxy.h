// TamperProxy: a TCP relay on loopback between agents and radfarmd that plays the attacker on the
// path. On its first `tampered_connections` connections it flips one bit in the first frame the
// agent sends after the handshake that is longer than `min_frame_bytes` (a LeaseResult rather
// than a Heartbeat); everything else passes unchanged. It runs on its own thread.
#pragma once

#include <atomic>
#include <cstdint>
#include <string>
#include <thread>

namespace radfarm::testing {

class TamperProxy {
 public:
  TamperProxy(std::string target, int tampered_connections, uint32_t min_frame_bytes = 200);
  ~TamperProxy();
  TamperProxy(const TamperProxy&) = delete;
  TamperProxy& operator=(const TamperProxy&) = delete;

  // "127.0.0.1:PORT": point the agent here.
  const std::string& address() const { return address_; }
  int connections() const { return connections_.load(); }
  int flips() const { return flips_.load(); }

 private:
  void Run();

  std::string target_;
  int tampered_connections_;
  uint32_t min_frame_bytes_;
  int listen_fd_ = -1;
  int stop_pipe_[2] = {-1, -1};
  std::string address_;
  std::atomic<int> connections_{0};
  std::atomic<int> flips_{0};
  std::thread thread_;
};

}  // namespace radfarm::testing
