// The control socket's requests and responses as the master sees them (docs/CONTROL.md). The
// control server parses and checks the JSON; the master answers with a JSON body (and, for fetch,
// an attachment).
#pragma once

#include <cstdint>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace radfarm::daemon {

enum class ControlCommand {
  kSubmit,
  kList,
  kStatus,
  kCancel,
  kPause,
  kResume,
  kLog,
  kFetch,
  kAgents,
  kEnrollAgent,
  kRevokeAgent,
  kEnrolledAgents
};

struct ControlRequest {
  ControlCommand command = ControlCommand::kList;
  // status, cancel, pause, resume, fetch: required; log: optional. Any unsigned 64-bit number:
  // one above the store's largest id is simply no job.
  std::optional<uint64_t> id;
  std::string name;                 // submit; enroll_agent, revoke_agent: the agent's name
  int64_t priority = 0;             // submit
  int64_t limit = 100;              // log
  std::vector<uint8_t> attachment;  // submit: the job bundle
};

struct ControlResponse {
  nlohmann::json body;              // has "ok"
  std::vector<uint8_t> attachment;  // fetch: the job solution
};

using ControlRespond = std::function<void(ControlResponse)>;

// {"ok": false, "error": message, "code": code}; code is bad_request, not_found, invalid_state or
// internal.
ControlResponse ControlError(const std::string& code, const std::string& message);

// The text of a JSON value for the wire. Strings that are not UTF-8 (a scene path in Latin-1, a
// job name from a bundle with 0xFF in it) have each bad byte replaced by U+FFFD instead of
// throwing: names are for people, and an exception here would end the daemon.
std::string JsonText(const nlohmann::json& value);

}  // namespace radfarm::daemon
