#include "protocol/messages.h"

namespace radfarm::protocol {
namespace {

// One name per Message alternative, in variant order.
constexpr std::string_view kMessageNames[] = {
    "Hello",       "Challenge",   "Proof",           "Welcome",     "Heartbeat",
    "LeaseReturn", "Cancel",      "SceneRequest",    "SceneChunk",  "SceneUnavailable",
    "Drain",       "Close",       "LeaseAssignment", "LeaseResult", "LeaseRevoke",
    "PointLease",  "PointResult",
};
static_assert(std::size(kMessageNames) == std::variant_size_v<Message>);

}  // namespace

std::string_view MessageName(const Message& message) { return kMessageNames[message.index()]; }

bool InVersion(const Message& message, uint16_t version) {
  if (const auto* lease = std::get_if<PointLeaseMsg>(&message)) {
    return version >= (lease->score_elements > 0   ? kScoreLeaseVersion
                       : lease->start_sections > 0 ? kStartLeaseVersion
                                                   : kPointLeaseVersion);
  }
  if (const auto* result = std::get_if<PointResultMsg>(&message)) {
    return version >= (!result->scores.empty()     ? kScoreLeaseVersion
                       : !result->punctual.empty() ? kStartLeaseVersion
                                                   : kPointLeaseVersion);
  }
  if (std::holds_alternative<LeaseAssignmentMsg>(message) ||
      std::holds_alternative<LeaseResultMsg>(message) ||
      std::holds_alternative<LeaseRevokeMsg>(message)) {
    return version >= 2;
  }
  return true;
}

std::string_view CloseCodeName(CloseCode code) {
  switch (code) {
    case CloseCode::kNormal:
      return "normal";
    case CloseCode::kShutdown:
      return "shutdown";
    case CloseCode::kProtocolError:
      return "protocol error";
    case CloseCode::kAuthFailed:
      return "authentication failed";
    case CloseCode::kVersionMismatch:
      return "version mismatch";
    case CloseCode::kInternalError:
      return "internal error";
    case CloseCode::kBlocklisted:
      return "blocklisted";
  }
  return "unknown";
}

}  // namespace radfarm::protocol
