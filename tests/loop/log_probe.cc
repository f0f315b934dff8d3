// log_probe TAG: writes one log line at each level, each naming TAG, for journal_integration_test.
#include <string>

#include "loop/log.h"

int main(int argc, char** argv) {
  using radfarm::loop::LogLevel;
  if (argc != 2) return 2;
  const std::string tag = argv[1];
  radfarm::loop::SetMinLogLevel(LogLevel::kDebug);
  radfarm::loop::Log(LogLevel::kDebug, "probe", tag + " debug");
  radfarm::loop::Log(LogLevel::kInfo, "probe", tag + " info");
  radfarm::loop::Log(LogLevel::kWarning, "probe", tag + " warning");
  radfarm::loop::Log(LogLevel::kError, "probe", tag + " error");
  return 0;
}
