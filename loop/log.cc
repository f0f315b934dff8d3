#include "loop/log.h"

#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <mutex>

#include "loop/journal_stream.h"

namespace radfarm::loop {
namespace {

std::atomic<int> min_level{static_cast<int>(LogLevel::kInfo)};

// Whether lines start with "<N>": unknown until the first line or DetectJournalStderr.
enum class PrefixMode { kUnknown, kPlain, kPriority };
std::atomic<PrefixMode> prefix_mode{PrefixMode::kUnknown};

PrefixMode DetectPrefixMode() {
  return FdIsJournalStream(STDERR_FILENO, std::getenv("JOURNAL_STREAM")) ? PrefixMode::kPriority
                                                                         : PrefixMode::kPlain;
}

bool WithPriorityPrefix() {
  PrefixMode mode = prefix_mode.load();
  if (mode == PrefixMode::kUnknown) {
    mode = DetectPrefixMode();
    prefix_mode.store(mode);
  }
  return mode == PrefixMode::kPriority;
}

std::mutex& SinkMutex() {
  static std::mutex mutex;
  return mutex;
}

LogSink& Sink() {
  static LogSink sink;
  return sink;
}

const char* LevelName(LogLevel level) {
  switch (level) {
    case LogLevel::kDebug:
      return "DEBUG";
    case LogLevel::kInfo:
      return "INFO ";
    case LogLevel::kWarning:
      return "WARN ";
    case LogLevel::kError:
      return "ERROR";
  }
  return "?????";
}

std::string Timestamp() {
  const auto now = std::chrono::system_clock::now();
  const std::time_t seconds = std::chrono::system_clock::to_time_t(now);
  const auto millis =
      std::chrono::duration_cast<std::chrono::milliseconds>(now.time_since_epoch()).count() % 1000;
  std::tm utc{};
  gmtime_r(&seconds, &utc);
  char text[64];  // roomy enough for any int fields (the compiler checks)
  std::snprintf(text, sizeof text, "%04d-%02d-%02dT%02d:%02d:%02d.%03dZ", utc.tm_year + 1900,
                utc.tm_mon + 1, utc.tm_mday, utc.tm_hour, utc.tm_min, utc.tm_sec,
                static_cast<int>(millis));
  return text;
}

void AppendEscaped(std::string& out, std::string_view text) {
  for (char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte < 0x20 || byte == 0x7f) {
      char escaped[5];
      std::snprintf(escaped, sizeof escaped, "\\x%02x", byte);
      out += escaped;
    } else {
      out += c;
    }
  }
}

void WriteAll(int fd, std::string_view bytes) {
  while (!bytes.empty()) {
    const ssize_t n = ::write(fd, bytes.data(), bytes.size());
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return;  // nowhere left to report a failing stderr
    bytes.remove_prefix(static_cast<size_t>(n));
  }
}

}  // namespace

int SyslogPriority(LogLevel level) {
  switch (level) {
    case LogLevel::kDebug:
      return 7;
    case LogLevel::kInfo:
      return 6;
    case LogLevel::kWarning:
      return 4;
    case LogLevel::kError:
      return 3;
  }
  return 6;
}

void DetectJournalStderr() { prefix_mode.store(DetectPrefixMode()); }

bool LogEnabled(LogLevel level) { return static_cast<int>(level) >= min_level.load(); }

void SetMinLogLevel(LogLevel level) { min_level.store(static_cast<int>(level)); }

void SetLogSink(LogSink sink) {
  std::lock_guard lock(SinkMutex());
  Sink() = std::move(sink);
}

void Log(LogLevel level, std::string_view component, std::string_view message) {
  if (!LogEnabled(level)) return;
  std::string line;
  if (WithPriorityPrefix()) line = "<" + std::to_string(SyslogPriority(level)) + ">";
  line += Timestamp();
  line += ' ';
  line += LevelName(level);
  line += ' ';
  AppendEscaped(line, component);
  line += ": ";
  AppendEscaped(line, message);
  std::lock_guard lock(SinkMutex());
  if (Sink()) {
    Sink()(line);
  } else {
    line += '\n';
    WriteAll(STDERR_FILENO, line);
  }
}

LogLine::LogLine(LogLevel level, std::string_view component)
    : level_(level), component_(component), enabled_(LogEnabled(level)) {}

LogLine::~LogLine() {
  if (enabled_) Log(level_, component_, stream_.str());
}

}  // namespace radfarm::loop
