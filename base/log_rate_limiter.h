// LogRateLimiter: at most `lines` log lines per window for one kind of event, so that a flood
// (thousands of strangers connecting and closing, or sending junk HTTP) cannot fill the journal or
// cost its thread time in writes. What it holds back is counted and said in one summary line once
// the window is over. Pure logic with the clock passed in; not thread-safe: one owner, or a mutex.
#pragma once

#include <chrono>
#include <cstdint>
#include <optional>

namespace radfarm {

class LogRateLimiter {
 public:
  using TimePoint = std::chrono::steady_clock::time_point;
  using Duration = std::chrono::steady_clock::duration;

  LogRateLimiter(uint32_t lines, Duration window) : lines_(lines), window_(window) {}

  // Whether the event seen at `now` may be logged; a false answer counts it as suppressed.
  bool Allow(TimePoint now);
  // Once a window with suppressed events has ended: how many were held back (then zero again).
  // Call it from a timer, so the summary comes even when the flood has stopped.
  std::optional<uint64_t> TakeSuppressed(TimePoint now);

  uint64_t suppressed_total() const { return suppressed_total_; }

 private:
  void Roll(TimePoint now);

  const uint32_t lines_;
  const Duration window_;
  std::optional<TimePoint> window_start_;
  uint32_t logged_ = 0;      // in the current window
  uint64_t suppressed_ = 0;  // since the last summary
  uint64_t suppressed_total_ = 0;
};

}  // namespace radfarm
