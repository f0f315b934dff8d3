// `radfarm log [ID] [--limit N]`: the master's events, oldest first: one job's, or the farm-wide
// log without an ID.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

namespace CLI {
class App;
}

namespace radfarm {

inline constexpr int64_t kDefaultLogLimit = 100;

struct LogOptions {
  std::optional<uint64_t> id;
  int64_t limit = kDefaultLogLimit;
  bool json = false;
};

CLI::App* AddLogCommand(CLI::App& app, LogOptions* options);
int RunLog(const LogOptions& options, const std::string& control_path);

}  // namespace radfarm
