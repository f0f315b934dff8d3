// `radfarm agents`: the agents connected to the master, with their speed, load and leases.
#pragma once

#include <string>

namespace CLI {
class App;
}

namespace radfarm {

struct AgentsOptions {
  bool json = false;
};

CLI::App* AddAgentsCommand(CLI::App& app, AgentsOptions* options);
int RunAgents(const AgentsOptions& options, const std::string& control_path);

}  // namespace radfarm
