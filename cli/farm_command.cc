#include "cli/farm_command.h"

#include <CLI/CLI.hpp>
#include <cstdio>

#include "cli/exit_codes.h"
#include "cli/messages.h"
#include "cli/option_checks.h"

namespace radfarm {
namespace {

using nlohmann::json;

template <typename T>
Outcome<std::vector<T>> ReplyArray(const ControlReply& reply, const std::string& command,
                                   const char* key,
                                   Result<T> (*parse)(const json&, const std::string&)) {
  const auto it = reply.body.find(key);
  if (it == reply.body.end())
    return MalformedResponse(command, std::string("missing key '") + key + "'");
  if (!it->is_array()) {
    return MalformedResponse(
        command, std::string("'") + key + "' is " + it->type_name() + ", expected an array");
  }
  std::vector<T> items;
  for (size_t i = 0; i < it->size(); ++i) {
    Result<T> item = parse((*it)[i], std::string(key) + "[" + std::to_string(i) + "]");
    if (!item.ok()) return MalformedResponse(command, item.error());
    items.push_back(std::move(*item));
  }
  return items;
}

}  // namespace

int ReportFailure(const Failure& failure) {
  PrintError(failure.message);
  return failure.exit_code;
}

Outcome<ControlReply> AskMaster(const std::string& socket_path, json request,
                                std::span<const uint8_t> attachment) {
  Outcome<ControlClient> client = ControlClient::Connect(socket_path);
  if (!client.ok()) return client.failure();
  return client->Call(std::move(request), attachment);
}

Outcome<JobInfo> ReplyJob(const ControlReply& reply, const std::string& command) {
  const auto it = reply.body.find("job");
  if (it == reply.body.end()) return MalformedResponse(command, "missing key 'job'");
  Result<JobInfo> job = ParseJob(*it, "job");
  if (!job.ok()) return MalformedResponse(command, job.error());
  return *job;
}

Outcome<std::vector<JobInfo>> ReplyJobs(const ControlReply& reply, const std::string& command) {
  return ReplyArray<JobInfo>(reply, command, "jobs", &ParseJob);
}

Outcome<std::vector<AgentInfo>> ReplyAgents(const ControlReply& reply, const std::string& command) {
  return ReplyArray<AgentInfo>(reply, command, "agents", &ParseAgent);
}

Outcome<std::vector<EventInfo>> ReplyEvents(const ControlReply& reply, const std::string& command) {
  return ReplyArray<EventInfo>(reply, command, "events", &ParseEvent);
}

void PrintJson(const json& value) {
  std::printf("%s\n", value.dump(2).c_str());
  std::fflush(stdout);
}

void AddJsonFlag(CLI::App* command, bool* json) {
  command->add_flag("--json", *json,
                    "Print the master's objects as JSON (their fields: CONTROL.md)");
}

void AddJobIdArgument(CLI::App* command, uint64_t* id) {
  command->add_option("ID", *id, "Job id (from submit or list)")->required()->check(PositiveId());
}

}  // namespace radfarm
