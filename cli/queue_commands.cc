#include "cli/queue_commands.h"

#include <CLI/CLI.hpp>
#include <cstdio>

#include "cli/exit_codes.h"
#include "cli/farm_command.h"
#include "cli/farm_format.h"

namespace radfarm {

CLI::App* AddListCommand(CLI::App& app, ListOptions* options) {
  CLI::App* list = app.add_subcommand("list", "List the master's jobs");
  AddJsonFlag(list, &options->json);
  return list;
}

int RunList(const ListOptions& options, const std::string& control_path) {
  Outcome<ControlReply> reply = AskMaster(control_path, {{"command", "list"}});
  if (!reply.ok()) return ReportFailure(reply.failure());
  Outcome<std::vector<JobInfo>> jobs = ReplyJobs(*reply, "list");
  if (!jobs.ok()) return ReportFailure(jobs.failure());
  if (options.json) {
    PrintJson(reply->body["jobs"]);
  } else if (jobs->empty()) {
    std::printf("no jobs\n");
  } else {
    std::printf("%s", FormatJobTable(*jobs).c_str());
  }
  return kExitOk;
}

CLI::App* AddJobActionCommand(CLI::App& app, const std::string& command,
                              const std::string& description, JobActionOptions* options) {
  options->command = command;
  CLI::App* action = app.add_subcommand(command, description);
  AddJobIdArgument(action, &options->id);
  AddJsonFlag(action, &options->json);
  return action;
}

int RunJobAction(const JobActionOptions& options, const std::string& control_path) {
  Outcome<ControlReply> reply =
      AskMaster(control_path, {{"command", options.command}, {"id", options.id}});
  if (!reply.ok()) return ReportFailure(reply.failure());
  Outcome<JobInfo> job = ReplyJob(*reply, options.command);
  if (!job.ok()) return ReportFailure(job.failure());
  if (options.json) {
    PrintJson(reply->body["job"]);
  } else {
    std::printf("job %lld (%s): %s\n", static_cast<long long>(job->id), job->name.c_str(),
                job->state.c_str());
  }
  return kExitOk;
}

}  // namespace radfarm
