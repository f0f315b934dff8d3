// radfarm: the command-line front end. Subcommands:
//   render                      the embedded single-machine mode (render_command.h)
//   submit list status cancel   the master's job queue, through its control socket
//   pause resume log fetch      (docs/CONTROL.md; farm_command.h)
//   agents [enroll NAME | revoke NAME]   per-agent keys (agent_credential_commands.h)
//   secret new                  a fresh farm secret (secret_command.h)
//   building                    a procedural building scene (building_command.h, scenegen/)
//   blender-addon install       the Blender add-on into Blender's add-ons folder
//                               (blender_addon_command.h, blender/)
#include <CLI/CLI.hpp>
#include <functional>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "cli/agent_credential_commands.h"
#include "cli/agents_command.h"
#include "cli/blender_addon_command.h"
#include "cli/building_command.h"
#include "cli/control_client.h"
#include "cli/exit_codes.h"
#include "cli/fetch_command.h"
#include "cli/log_command.h"
#include "cli/messages.h"
#include "cli/queue_commands.h"
#include "cli/render_command.h"
#include "cli/secret_command.h"
#include "cli/status_command.h"
#include "cli/submit_command.h"

namespace {

// CLI11 checks required options and subcommands before it complains about arguments it does not
// know, so `radfarm bogus` said "A subcommand is required" and `render --bogus x` "--out is
// required". An argument nobody knows is the first thing to name.
CLI::Error UnknownArgumentsFirst(const CLI::App& app, const CLI::ParseError& error) {
  const std::vector<std::string> unknown = app.remaining(/*recurse=*/true);
  if (unknown.empty()) return error;
  if (app.get_subcommands().empty() && !unknown.front().starts_with('-')) {
    std::string names;
    for (const CLI::App* command : app.get_subcommands([](const CLI::App*) { return true; }))
      names += (names.empty() ? "" : ", ") + command->get_name();
    return CLI::Error("UnknownSubcommand",
                      "unknown subcommand '" + unknown.front() + "' (one of " + names + ")",
                      CLI::ExitCodes::ExtrasError);
  }
  return CLI::ExtrasError(unknown);
}

}  // namespace

int main(int argc, char** argv) {
  using namespace radfarm;
  CLI::App app{"radfarm: progressive-refinement radiosity on one machine or a farm"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "radfarm 0.1.0");
  // Usage errors look like every other error: one "radfarm: " line on stderr.
  app.failure_message([](const CLI::App*, const CLI::Error& e) {
    return "radfarm: " + std::string(e.what()) + " (see --help)\n";
  });
  // Subcommands inherit this, so --control may also come after the command's name.
  app.fallthrough();
  std::string control = DefaultControlPath();
  app.add_option("--control", control,
                 std::string("The master's control socket (default: $RADFARM_CONTROL if set, "
                             "else ") +
                     kDefaultControlPath + ")");

  // Each subcommand with the function that runs it once the command line is parsed.
  std::vector<std::pair<CLI::App*, std::function<int()>>> commands;
  RenderOptions render;
  commands.emplace_back(AddRenderCommand(app, &render), [&] { return RunRender(render); });
  SubmitOptions submit;
  commands.emplace_back(AddSubmitCommand(app, &submit), [&] { return RunSubmit(submit, control); });
  ListOptions list;
  commands.emplace_back(AddListCommand(app, &list), [&] { return RunList(list, control); });
  StatusOptions status;
  commands.emplace_back(AddStatusCommand(app, &status), [&] { return RunStatus(status, control); });
  JobActionOptions cancel, pause, resume;
  for (auto& [options, name, description] :
       {std::tuple(&cancel, "cancel", "Cancel a job (it keeps its latest checkpoint)"),
        std::tuple(&pause, "pause", "Pause a job: no new rounds until resume"),
        std::tuple(&resume, "resume", "Queue a paused job again")}) {
    commands.emplace_back(AddJobActionCommand(app, name, description, options),
                          [options, &control] { return RunJobAction(*options, control); });
  }
  LogOptions log;
  commands.emplace_back(AddLogCommand(app, &log), [&] { return RunLog(log, control); });
  FetchOptions fetch;
  commands.emplace_back(AddFetchCommand(app, &fetch), [&] { return RunFetch(fetch, control); });
  // enroll, revoke and enrolled before agents: `agents` counts as parsed when one of them is.
  AgentsOptions agents;
  CLI::App* agents_command = AddAgentsCommand(app, &agents);
  EnrollOptions enroll;
  commands.emplace_back(AddEnrollCommand(*agents_command, &enroll),
                        [&] { return RunEnroll(enroll, control); });
  RevokeOptions revoke;
  commands.emplace_back(AddRevokeCommand(*agents_command, &revoke),
                        [&] { return RunRevoke(revoke, control); });
  EnrolledOptions enrolled;
  commands.emplace_back(AddEnrolledCommand(*agents_command, &enrolled),
                        [&] { return RunEnrolled(enrolled, control); });
  commands.emplace_back(agents_command, [&] { return RunAgents(agents, control); });
  SecretOptions secret;
  commands.emplace_back(AddSecretCommand(app, &secret), [&] { return RunSecretNew(secret); });
  BuildingOptions building;
  commands.emplace_back(AddBuildingCommand(app, &building), [&] { return RunBuilding(building); });
  BlenderAddonOptions blender_addon;
  commands.emplace_back(AddBlenderAddonCommand(app, &blender_addon),
                        [&] { return RunBlenderAddonInstall(blender_addon); });

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e) == 0 ? kExitOk : kExitBadInput;  // --help
    app.exit(UnknownArgumentsFirst(app, e));
    return kExitBadInput;
  }
  for (const auto& [command, run] : commands) {
    if (!command->parsed()) continue;
    // Thread pools throw when the system refuses a thread (a process or memory limit).
    try {
      return run();
    } catch (const std::system_error& e) {
      PrintError(std::string("cannot start the threads this command needs: ") + e.what());
      return kExitFailure;
    }
  }
  return kExitBadInput;
}
