// radfarm: the command-line front end. Subcommands:
//   render   the embedded single-machine mode (render_command.h)
#include <CLI/CLI.hpp>
#include <functional>
#include <utility>
#include <vector>

#include "cli/exit_codes.h"
#include "cli/render_command.h"

int main(int argc, char** argv) {
  using namespace radfarm;
  CLI::App app{"radfarm: progressive-refinement radiosity on one machine or a farm"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "radfarm 0.1.0");

  // Each subcommand with the function that runs it once the command line is parsed.
  std::vector<std::pair<CLI::App*, std::function<int()>>> commands;
  RenderOptions render;
  commands.emplace_back(AddRenderCommand(app, &render), [&] { return RunRender(render); });

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? kExitOk : kExitBadInput;
  }
  for (const auto& [command, run] : commands) {
    if (command->parsed()) return run();
  }
  return kExitBadInput;
}
