// Helpers for the loop tests: run a loop until a condition holds (never a fixed sleep), prove a
// loop closes clean, and a plain blocking socket client for byte-level tests.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "loop/event_loop.h"

namespace radfarm::loop::testing {

inline constexpr std::chrono::milliseconds kTimeout{30000};  // generous: 2 shared cores

// Runs `loop` until `done()` holds, re-checking at least every 5 ms. False after `timeout`.
bool RunUntil(EventLoop& loop, const std::function<bool()>& done,
              std::chrono::milliseconds timeout = kTimeout);

// Polls `done` every millisecond without running any loop, for conditions other threads bring
// about. False after `timeout`.
bool WaitFor(const std::function<bool()>& done, std::chrono::milliseconds timeout = kTimeout);

// Every loop test ends here: all handles closed and uv_loop_close() == 0.
void ExpectClosesClean(EventLoop& loop);

// A unique path for a Unix socket (short enough for sun_path), removed by the caller's test.
std::string TempSocketPath(const std::string& name);

// One frame as bytes on the wire.
std::vector<uint8_t> Frame(const std::vector<uint8_t>& payload);
std::vector<uint8_t> Bytes(const std::string& text);

// A blocking TCP or Unix client that talks raw bytes, outside the loop.
class RawClient {
 public:
  ~RawClient();
  bool ConnectTcp(const std::string& host, uint16_t port);
  bool ConnectUnix(const std::string& path);
  bool SendAll(const std::vector<uint8_t>& bytes);
  // Appends whatever has arrived, without blocking. False once the peer has closed.
  bool ReadAvailable(std::vector<uint8_t>* out);
  void SetReceiveBuffer(int bytes);
  void Close();
  int fd() const { return fd_; }

 private:
  int fd_ = -1;
};

}  // namespace radfarm::loop::testing
