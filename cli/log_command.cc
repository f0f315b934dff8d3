#include "cli/log_command.h"

#include <CLI/CLI.hpp>
#include <cstdio>

#include "cli/exit_codes.h"
#include "cli/farm_command.h"
#include "cli/farm_format.h"
#include "cli/option_checks.h"

namespace radfarm {

CLI::App* AddLogCommand(CLI::App& app, LogOptions* options) {
  CLI::App* log = app.add_subcommand(
      "log",
      "Show a job's events, or without an ID the whole farm's: every job's and the farm's own "
      "(oldest first)");
  log->add_option("ID", options->id, "Job id (default: every job's events and the farm's)")
      ->check(PositiveId());
  log->add_option("--limit,-n", options->limit, "Show the last N events (default 100)")
      ->check(PositiveInteger());
  AddJsonFlag(log, &options->json);
  return log;
}

int RunLog(const LogOptions& options, const std::string& control_path) {
  nlohmann::json request = {{"command", "log"}, {"limit", options.limit}};
  if (options.id) request["id"] = *options.id;
  Outcome<ControlReply> reply = AskMaster(control_path, request);
  if (!reply.ok()) return ReportFailure(reply.failure());
  Outcome<std::vector<EventInfo>> events = ReplyEvents(*reply, "log");
  if (!events.ok()) return ReportFailure(events.failure());
  if (options.json) {
    PrintJson(reply->body["events"]);
    return kExitOk;
  }
  for (const EventInfo& e : *events) std::printf("%s\n", FormatEvent(e).c_str());
  return kExitOk;
}

}  // namespace radfarm
