// ControlClient: the blocking client side of the master's control socket (docs/CONTROL.md). One
// connection, one request at a time: send a JSON frame (plus an attachment frame), read the JSON
// response (plus its attachment frame). Every send and receive times out after
// kControlTimeoutSeconds, so a wedged master ends a command with an error rather than a hang.
//
// Failures carry their exit code: the socket cannot be connected (missing, refused, permission
// denied) -> kExitUnreachable; the master answers {"ok": false} -> the code's exit code
// (ExitCodeForErrorCode); the exchange breaks or the response is malformed -> kExitFailure.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "base/unique_fd.h"
#include "cli/command_outcome.h"

namespace radfarm {

inline constexpr char kDefaultControlPath[] = "/var/lib/radfarm/control.sock";
inline constexpr int kControlTimeoutSeconds = 30;

// $RADFARM_CONTROL when set and not empty, else kDefaultControlPath.
std::string DefaultControlPath();

// bad_request and not_found -> kExitBadInput; invalid_state, internal and codes this client does
// not know -> kExitFailure.
int ExitCodeForErrorCode(std::string_view code);

// A response that breaks docs/CONTROL.md: exit 1, "malformed response from the master to
// 'COMMAND': WHY".
Failure MalformedResponse(const std::string& command, const std::string& why);

struct ControlReply {
  nlohmann::json body;              // the response object; body["ok"] is true
  std::vector<uint8_t> attachment;  // the frame that followed it, when it had attachment_bytes
};

class ControlClient {
 public:
  static Outcome<ControlClient> Connect(const std::string& socket_path);

  // Sends `request` ({"command": ..., arguments}); a non-empty `attachment` is announced with
  // "attachment_bytes" and sent as the next frame. Reads the response and, when it announces
  // attachment_bytes, the attachment. An {"ok": false} response becomes a Failure carrying the
  // master's message.
  Outcome<ControlReply> Call(nlohmann::json request, std::span<const uint8_t> attachment = {});

  const std::string& socket_path() const { return socket_path_; }

 private:
  ControlClient(UniqueFd fd, std::string socket_path)
      : fd_(std::move(fd)), socket_path_(std::move(socket_path)) {}

  Outcome<ControlReply> ReadReply(const std::string& command);

  UniqueFd fd_;
  std::string socket_path_;
};

}  // namespace radfarm
