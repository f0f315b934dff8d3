// `radfarm list` and the job actions `radfarm cancel|pause|resume ID`: one request each, the
// answer printed as a table or a line (or, with --json, as the master's objects).
#pragma once

#include <cstdint>
#include <string>

namespace CLI {
class App;
}

namespace radfarm {

struct ListOptions {
  bool json = false;
};

CLI::App* AddListCommand(CLI::App& app, ListOptions* options);
int RunList(const ListOptions& options, const std::string& control_path);

// A request that changes one job's state and answers with the job: cancel, pause or resume.
struct JobActionOptions {
  std::string command;  // the control command's name, also the subcommand's
  uint64_t id = 0;
  bool json = false;
};

CLI::App* AddJobActionCommand(CLI::App& app, const std::string& command,
                              const std::string& description, JobActionOptions* options);
int RunJobAction(const JobActionOptions& options, const std::string& control_path);

}  // namespace radfarm
