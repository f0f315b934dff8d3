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
  kAgents
};

struct ControlRequest {
  ControlCommand command = ControlCommand::kList;
  std::optional<int64_t> id;        // status, cancel, pause, resume, fetch: required; log: optional
  std::string name;                 // submit
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

}  // namespace radfarm::daemon
