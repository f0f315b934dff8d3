// Log: one line per event on stderr, e.g.
//
//   2024-05-01T12:34:56.789Z WARN  scheduler: lease 12 expired
//
// Thread-safe: each line is formatted first and written with one write(2) under a mutex, so lines
// from different threads never interleave. Control characters in the component or message are
// escaped (a newline becomes \x0a), so a peer-supplied string (an agent name, a close reason)
// cannot forge a second line.
//
// Never log secrets: not the farm secret, not HMAC keys, nonces or tags, not tokens. Log lines are
// copied to terminals, journald and bug reports, where a secret must not go.
#pragma once

#include <functional>
#include <sstream>
#include <string>
#include <string_view>

namespace radfarm::loop {

enum class LogLevel { kDebug, kInfo, kWarning, kError };

// Writes one line if `level` is at least the minimum level.
void Log(LogLevel level, std::string_view component, std::string_view message);

// Lines below `level` are dropped. Default: kInfo. Any thread.
void SetMinLogLevel(LogLevel level);
bool LogEnabled(LogLevel level);

// Where lines go (without their trailing newline); an empty function restores stderr. For tests.
// The sink is called under the log mutex: it must not log.
using LogSink = std::function<void(std::string_view line)>;
void SetLogSink(LogSink sink);

// Stream style: LogLine(LogLevel::kInfo, "master") << "listening on " << address;
// The line is written when the temporary is destroyed, at the end of the statement.
class LogLine {
 public:
  LogLine(LogLevel level, std::string_view component);
  ~LogLine();
  LogLine(const LogLine&) = delete;
  LogLine& operator=(const LogLine&) = delete;

  template <typename T>
  LogLine& operator<<(const T& value) {
    if (enabled_) stream_ << value;
    return *this;
  }

 private:
  LogLevel level_;
  std::string component_;
  bool enabled_;
  std::ostringstream stream_;
};

}  // namespace radfarm::loop
