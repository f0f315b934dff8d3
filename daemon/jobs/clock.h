// Clock: the master's time as its rooms read it (JobRounds, AgentConnections, AgentLink,
// ControlRequests), so that a test drives it by hand, as LevelDB's Env lets a test fake only the
// clock. Milliseconds on a monotonic clock with an arbitrary origin; it never goes back.
//
// radfarmd's is LoopClock: the event loop's cached time (uv_now), which libuv updates once per
// loop iteration, so every callback of one iteration reads the same time. Loop thread only.
#pragma once

#include <chrono>
#include <cstdint>

#include "daemon/scheduler/scheduler_types.h"
#include "loop/event_loop.h"

namespace radfarm::daemon {

class Clock {
 public:
  virtual ~Clock() = default;
  virtual uint64_t NowMs() const = 0;

  // The same time as the schedulers read it (daemon/scheduler/).
  scheduler::TimePoint Now() const {
    return scheduler::TimePoint(std::chrono::milliseconds(NowMs()));
  }
};

class LoopClock final : public Clock {
 public:
  explicit LoopClock(const loop::EventLoop& loop) : loop_(loop) {}
  uint64_t NowMs() const override { return loop_.NowMs(); }

 private:
  const loop::EventLoop& loop_;
};

}  // namespace radfarm::daemon
