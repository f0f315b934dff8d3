// What the farm commands (submit, list, status, cancel, pause, resume, log, fetch, agents) share:
// one exchange with the master, strict reading of the objects in its answer, failure reporting,
// and the options every one of them has.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <vector>

#include "cli/command_outcome.h"
#include "cli/control_client.h"
#include "cli/control_objects.h"

namespace CLI {
class App;
}

namespace radfarm {

// Prints "radfarm: MESSAGE" to stderr and returns the failure's exit code.
int ReportFailure(const Failure& failure);

// Connects to the master at `socket_path` and makes one request.
Outcome<ControlReply> AskMaster(const std::string& socket_path, nlohmann::json request,
                                std::span<const uint8_t> attachment = {});

// The checked object or array of objects under `key` in a reply to `command`. A missing key or a
// malformed object is a failure (exit 1) naming the key ("jobs[2].round").
Outcome<JobInfo> ReplyJob(const ControlReply& reply, const std::string& command);
Outcome<std::vector<JobInfo>> ReplyJobs(const ControlReply& reply, const std::string& command);
Outcome<std::vector<AgentInfo>> ReplyAgents(const ControlReply& reply, const std::string& command);
Outcome<std::vector<EventInfo>> ReplyEvents(const ControlReply& reply, const std::string& command);

// Pretty-printed JSON (keys sorted, two-space indent) and a newline on stdout.
void PrintJson(const nlohmann::json& value);

// --json: "print the master's objects as JSON (docs/CONTROL.md)".
void AddJsonFlag(CLI::App* command, bool* json);
// The positional job ID (a positive integer).
// Any unsigned 64-bit id >= 1: one the master does not know is its "no job ID" (exit 2).
void AddJobIdArgument(CLI::App* command, uint64_t* id);

}  // namespace radfarm
