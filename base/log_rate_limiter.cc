#include "base/log_rate_limiter.h"

namespace radfarm {

void LogRateLimiter::Roll(TimePoint now) {
  if (!window_start_ || now - *window_start_ >= window_) {
    window_start_ = now;
    logged_ = 0;
  }
}

bool LogRateLimiter::Allow(TimePoint now) {
  Roll(now);
  if (logged_ < lines_) {
    ++logged_;
    return true;
  }
  ++suppressed_;
  ++suppressed_total_;
  return false;
}

std::optional<uint64_t> LogRateLimiter::TakeSuppressed(TimePoint now) {
  if (suppressed_ == 0 || !window_start_ || now - *window_start_ < window_) return std::nullopt;
  const uint64_t n = suppressed_;
  suppressed_ = 0;
  // The summary takes the place of the window's first line: the next window starts now.
  window_start_ = now;
  logged_ = 0;
  return n;
}

}  // namespace radfarm
