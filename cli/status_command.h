// `radfarm status ID [--watch]`: a job's state, round, unshot power, rays/s, agents and ETA. With
// --watch it polls the master every kWatchIntervalMs until the job ends (WatchPrinter shows it)
// and exits 0 when the job is done, 1 when it failed or was cancelled.
#pragma once

#include <cstdint>
#include <string>

namespace CLI {
class App;
}

namespace radfarm {

inline constexpr int kWatchIntervalMs = 500;

struct StatusOptions {
  uint64_t id = 0;
  bool watch = false;
  bool json = false;
};

CLI::App* AddStatusCommand(CLI::App& app, StatusOptions* options);
int RunStatus(const StatusOptions& options, const std::string& control_path);

}  // namespace radfarm
