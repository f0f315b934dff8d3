// Log: one line per event on stderr, e.g.
//
//   2024-05-01T12:34:56.789Z WARN  scheduler: lease 12 expired
//
// Thread-safe: each line is formatted first and written with one write(2) under a mutex, so lines
// from different threads never interleave. Control characters in the component or message are
// escaped (a newline becomes \x0a), so a peer-supplied string (an agent name, a close reason)
// cannot forge a second line.
//
// Under systemd, when stderr is the journal's stream ($JOURNAL_STREAM names it: journal_stream.h),
// each line starts with its syslog priority, "<3>" error, "<4>" warning, "<6>" info, "<7>" debug,
// which journald stores as the entry's PRIORITY and strips from the message, so `journalctl -p
// warning` shows warnings and errors only.
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

// The syslog priority of `level` (syslog(3): LOG_ERR 3, LOG_WARNING 4, LOG_INFO 6, LOG_DEBUG 7).
int SyslogPriority(LogLevel level);

// Looks again whether stderr is the journal's stream and so whether lines carry "<N>" prefixes.
// The first line looks by itself; call this after redirecting stderr or changing $JOURNAL_STREAM.
void DetectJournalStderr();

// Lines below `level` are dropped. Default: kInfo. Any thread.
void SetMinLogLevel(LogLevel level);
bool LogEnabled(LogLevel level);

// Where lines go (without their trailing newline, with the priority prefix when stderr is the
// journal); an empty function restores stderr. For tests.
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
