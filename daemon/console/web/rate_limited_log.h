// RateLimitedLog: warnings of one kind from any thread, at most `lines` per window (LogRateLimiter
// under a mutex), so a client sending junk cannot fill the journal. The lines held back are
// counted in one summary line, written with the first line of a later window or by Flush.
//
// Thread-safe: the HTTP threads share one.
#pragma once

#include <chrono>
#include <cstdint>
#include <mutex>
#include <string>
#include <string_view>

#include "base/log_rate_limiter.h"

namespace radfarm::web {

class RateLimitedLog {
 public:
  using TimePoint = LogRateLimiter::TimePoint;

  // `what` names the lines in the summary: "N more WHAT were not logged (...)".
  RateLimitedLog(std::string component, std::string what, uint32_t lines,
                 std::chrono::seconds window);

  void Warn(std::string_view line) { Warn(line, std::chrono::steady_clock::now()); }
  void Warn(std::string_view line, TimePoint now);
  // Writes the summary of a window that has ended, if it held lines back.
  void Flush(TimePoint now);

 private:
  void FlushLocked(TimePoint now);

  const std::string component_;
  const std::string what_;
  const uint32_t lines_;
  const std::chrono::seconds window_;
  std::mutex mutex_;
  LogRateLimiter limiter_;
};

}  // namespace radfarm::web
