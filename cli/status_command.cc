#include "cli/status_command.h"

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <thread>

#include "cli/exit_codes.h"
#include "cli/farm_command.h"
#include "cli/farm_format.h"
#include "cli/messages.h"
#include "cli/watch_printer.h"

namespace radfarm {
namespace {

nlohmann::json StatusRequest(uint64_t id) { return {{"command", "status"}, {"id", id}}; }

int Watch(const StatusOptions& options, const std::string& control_path) {
  // One connection for the whole watch: the protocol allows any number of requests on it.
  Outcome<ControlClient> client = ControlClient::Connect(control_path);
  if (!client.ok()) return ReportFailure(client.failure());
  const WatchStyle style = options.json                 ? WatchStyle::kJsonLines
                           : isatty(STDOUT_FILENO) == 1 ? WatchStyle::kBar
                                                        : WatchStyle::kLines;
  WatchPrinter printer(stdout, style);
  for (;;) {
    Outcome<ControlReply> reply = client->Call(StatusRequest(options.id));
    Outcome<JobInfo> job = reply.ok() ? ReplyJob(*reply, "status") : reply.failure();
    if (!job.ok()) {
      printer.Finish();
      return ReportFailure(job.failure());
    }
    printer.Show(*job, reply->body["job"]);
    if (IsTerminalState(job->state)) {
      printer.Finish();
      if (job->state == "done") return kExitOk;
      PrintError("job " + std::to_string(job->id) + " " + job->state +
                 (job->error ? ": " + *job->error : std::string()));
      return kExitFailure;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(kWatchIntervalMs));
  }
}

}  // namespace

CLI::App* AddStatusCommand(CLI::App& app, StatusOptions* options) {
  CLI::App* status = app.add_subcommand(
      "status", "Show a job's state, round, unshot power, rays/s, agents and ETA");
  AddJobIdArgument(status, &options->id);
  status->add_flag("--watch,-w", options->watch,
                   "Follow the job until it ends: a progress bar on a terminal, a line per change "
                   "otherwise; exit 0 when done, 1 when failed or cancelled");
  AddJsonFlag(status, &options->json);
  return status;
}

int RunStatus(const StatusOptions& options, const std::string& control_path) {
  if (options.watch) return Watch(options, control_path);
  Outcome<ControlReply> reply = AskMaster(control_path, StatusRequest(options.id));
  if (!reply.ok()) return ReportFailure(reply.failure());
  Outcome<JobInfo> job = ReplyJob(*reply, "status");
  if (!job.ok()) return ReportFailure(job.failure());
  if (options.json) {
    PrintJson(reply->body["job"]);
  } else {
    std::printf("%s", FormatJobStatus(*job).c_str());
  }
  return kExitOk;
}

}  // namespace radfarm
