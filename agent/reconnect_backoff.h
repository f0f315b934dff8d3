// ReconnectBackoff: how long the agent waits before its next attempt to reach the master.
//
// The base delay starts at `initial`, doubles after every failed attempt and stops at `cap`; the
// delay actually used is drawn uniformly from [base / 2, base] ("equal jitter"), so agents that
// lost the same master do not all come back in the same millisecond, yet a delay never exceeds the
// cap and never falls below half the base. A connection that succeeded resets it: one on which the
// master sent a message after its Welcome (a handshake alone is not enough: a full master refuses
// right after it; agent/agent.cc).
//
// The random generator is seeded by the caller (tests pass a fixed seed). Jitter only moves the
// time of a reconnect; nothing computed depends on it.
#pragma once

#include <chrono>
#include <cstdint>
#include <random>

namespace radfarm::agent {

class ReconnectBackoff {
 public:
  struct Options {
    std::chrono::milliseconds initial{100};
    std::chrono::milliseconds cap{10000};
  };

  ReconnectBackoff(Options options, uint64_t seed);

  // The delay before the next attempt; then doubles the base (up to the cap).
  std::chrono::milliseconds Next();
  // Back to `initial`, after a connection that succeeded.
  void Reset();

  // The base the next delay is drawn under.
  std::chrono::milliseconds base() const { return base_; }

 private:
  Options options_;
  std::chrono::milliseconds base_;
  std::mt19937_64 random_;
};

}  // namespace radfarm::agent
