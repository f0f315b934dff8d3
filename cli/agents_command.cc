#include "cli/agents_command.h"

#include <CLI/CLI.hpp>
#include <cstdio>

#include "cli/exit_codes.h"
#include "cli/farm_command.h"
#include "cli/farm_format.h"

namespace radfarm {

CLI::App* AddAgentsCommand(CLI::App& app, AgentsOptions* options) {
  CLI::App* agents = app.add_subcommand("agents", "List the agents connected to the master");
  AddJsonFlag(agents, &options->json);
  return agents;
}

int RunAgents(const AgentsOptions& options, const std::string& control_path) {
  Outcome<ControlReply> reply = AskMaster(control_path, {{"command", "agents"}});
  if (!reply.ok()) return ReportFailure(reply.failure());
  Outcome<std::vector<AgentInfo>> agents = ReplyAgents(*reply, "agents");
  if (!agents.ok()) return ReportFailure(agents.failure());
  if (options.json) {
    PrintJson(reply->body["agents"]);
  } else if (agents->empty()) {
    std::printf("no agents connected\n");
  } else {
    std::printf("%s", FormatAgentTable(*agents).c_str());
  }
  return kExitOk;
}

}  // namespace radfarm
