#include "daemon/console/web/rate_limited_log.h"

#include "loop/log.h"

namespace radfarm::web {

RateLimitedLog::RateLimitedLog(std::string component, std::string what, uint32_t lines,
                               std::chrono::seconds window)
    : component_(std::move(component)),
      what_(std::move(what)),
      lines_(lines),
      window_(window),
      limiter_(lines, window) {}

void RateLimitedLog::Warn(std::string_view line, TimePoint now) {
  std::lock_guard lock(mutex_);
  FlushLocked(now);
  if (limiter_.Allow(now)) loop::Log(loop::LogLevel::kWarning, component_, line);
}

void RateLimitedLog::Flush(TimePoint now) {
  std::lock_guard lock(mutex_);
  FlushLocked(now);
}

void RateLimitedLog::FlushLocked(TimePoint now) {
  if (const std::optional<uint64_t> held_back = limiter_.TakeSuppressed(now)) {
    loop::LogLine(loop::LogLevel::kWarning, component_)
        << *held_back << " more " << what_ << " were not logged (at most " << lines_
        << " lines per " << window_.count() << " s)";
  }
}

}  // namespace radfarm::web
