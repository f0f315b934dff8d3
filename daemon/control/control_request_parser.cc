#include "daemon/control/control_request_parser.h"

#include <limits>
#include <string>

namespace radfarm::daemon {

namespace {

struct CommandName {
  const char* name;
  ControlCommand command;
};
constexpr CommandName kCommands[] = {
    {"submit", ControlCommand::kSubmit},
    {"list", ControlCommand::kList},
    {"status", ControlCommand::kStatus},
    {"cancel", ControlCommand::kCancel},
    {"pause", ControlCommand::kPause},
    {"resume", ControlCommand::kResume},
    {"log", ControlCommand::kLog},
    {"fetch", ControlCommand::kFetch},
    {"agents", ControlCommand::kAgents},
    {"enroll_agent", ControlCommand::kEnrollAgent},
    {"revoke_agent", ControlCommand::kRevokeAgent},
    {"enrolled_agents", ControlCommand::kEnrolledAgents},
};

Result<int64_t> IntArg(const nlohmann::json& json, const char* key) {
  const auto it = json.find(key);
  if (it == json.end() || !it->is_number_integer()) {
    return Error{std::string("'") + key + "' must be an integer"};
  }
  // nlohmann keeps numbers past INT64_MAX unsigned; get<int64_t> would wrap them to negatives.
  if (it->is_number_unsigned() &&
      it->get<uint64_t>() > uint64_t(std::numeric_limits<int64_t>::max())) {
    return Error{std::string("'") + key + "' must be an integer in [" +
                 std::to_string(std::numeric_limits<int64_t>::min()) + ", " +
                 std::to_string(std::numeric_limits<int64_t>::max()) + "]"};
  }
  return it->get<int64_t>();
}

// A job id: any unsigned 64-bit integer, kept as given so that errors can name it.
Result<uint64_t> IdArg(const nlohmann::json& json) {
  const auto it = json.find("id");
  if (it == json.end() || !it->is_number_integer()) return Error{"'id' must be an integer"};
  if (it->is_number_unsigned()) return it->get<uint64_t>();
  if (it->get<int64_t>() < 0) return Error{"'id' must not be negative"};
  return static_cast<uint64_t>(it->get<int64_t>());
}

}  // namespace

Result<ControlRequest> ParseControlRequest(const nlohmann::json& json, uint64_t* attachment_bytes) {
  *attachment_bytes = 0;
  if (!json.is_object()) return Error{"a request must be a JSON object"};
  const auto command = json.find("command");
  if (command == json.end() || !command->is_string()) {
    return Error{"'command' must be a string"};
  }
  ControlRequest request;
  bool known = false;
  for (const CommandName& c : kCommands) {
    if (*command == c.name) {
      request.command = c.command;
      known = true;
    }
  }
  if (!known) return Error{"unknown command '" + command->get<std::string>() + "'"};
  switch (request.command) {
    case ControlCommand::kStatus:
    case ControlCommand::kCancel:
    case ControlCommand::kPause:
    case ControlCommand::kResume:
    case ControlCommand::kFetch: {
      Result<uint64_t> id = IdArg(json);
      RADFARM_RETURN_IF_ERROR(id);
      request.id = *id;
      break;
    }
    case ControlCommand::kLog:
      if (json.contains("id") && !json["id"].is_null()) {
        Result<uint64_t> id = IdArg(json);
        RADFARM_RETURN_IF_ERROR(id);
        request.id = *id;
      }
      if (json.contains("limit")) {
        Result<int64_t> limit = IntArg(json, "limit");
        RADFARM_RETURN_IF_ERROR(limit);
        if (*limit < 1 || *limit > 100000) return Error{"'limit' must be in [1, 100000]"};
        request.limit = *limit;
      }
      break;
    case ControlCommand::kSubmit: {
      if (json.contains("name")) {
        if (!json["name"].is_string()) return Error{"'name' must be a string"};
        request.name = json["name"].get<std::string>();
        if (request.name.size() > 256) return Error{"'name' is longer than 256 bytes"};
      }
      if (json.contains("priority")) {
        Result<int64_t> priority = IntArg(json, "priority");
        RADFARM_RETURN_IF_ERROR(priority);
        request.priority = *priority;
      }
      Result<int64_t> bytes = IntArg(json, "attachment_bytes");
      if (!bytes) return Error{"submit needs the job bundle: " + bytes.error()};
      if (*bytes < 1 || uint64_t(*bytes) > kMaxControlAttachmentBytes) {
        return Error{"'attachment_bytes' must be in [1, " +
                     std::to_string(kMaxControlAttachmentBytes) + "]"};
      }
      *attachment_bytes = uint64_t(*bytes);
      break;
    }
    case ControlCommand::kEnrollAgent:
    case ControlCommand::kRevokeAgent: {
      const auto name = json.find("name");
      if (name == json.end() || !name->is_string()) return Error{"'name' must be a string"};
      request.name = name->get<std::string>();
      break;  // ControlRequests checks it is an agent name (protocol::IsValidAgentName)
    }
    case ControlCommand::kList:
    case ControlCommand::kAgents:
    case ControlCommand::kEnrolledAgents:
      break;
  }
  return request;
}

Result<nlohmann::json> ParseControlJson(std::span<const uint8_t> payload) {
  nlohmann::json json = nlohmann::json::parse(payload.begin(), payload.end(), nullptr, false);
  if (json.is_discarded()) return Error{"the request is not valid JSON"};
  return json;
}

}  // namespace radfarm::daemon
