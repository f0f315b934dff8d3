// FakeLogind: answers as org.freedesktop.login1's Manager (IdleHint, IdleSinceHintMonotonic) on
// direct sd-bus connections, one server thread per connection over a socketpair, so
// LogindUserIdle is tested against real D-Bus messages without a bus daemon or logind.
#pragma once

#include <atomic>
#include <cstdint>
#include <mutex>
#include <thread>
#include <vector>

#include "idle/logind_user_idle.h"

namespace radfarm::idle::testing {

class FakeLogind {
 public:
  FakeLogind() = default;
  ~FakeLogind();  // stops and joins every server thread
  FakeLogind(const FakeLogind&) = delete;
  FakeLogind& operator=(const FakeLogind&) = delete;

  // Connects a new client; the server side runs until the client hangs up or the fake dies.
  BusConnector Connector();
  void Set(bool idle_hint, uint64_t idle_since_monotonic_usec);
  int connections() const { return connections_.load(); }

  // Read by the property getters on the server threads.
  std::atomic<bool> idle_hint{true};
  std::atomic<uint64_t> idle_since_usec{0};
  // False: new connections answer no login1 object at all.
  std::atomic<bool> serve_manager{true};

 private:
  void Serve(int fd);

  std::atomic<bool> stop_{false};
  std::atomic<int> connections_{0};
  std::mutex mutex_;
  std::vector<std::thread> threads_;
};

uint64_t MonotonicNowUsec();

}  // namespace radfarm::idle::testing
