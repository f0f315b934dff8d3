#include "cli/control_client.h"

#include <sys/socket.h>
#include <sys/time.h>
#include <sys/un.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>

#include "cli/control_frames.h"
#include "cli/exit_codes.h"
#include "cli/printable.h"

namespace radfarm {
namespace {

using nlohmann::json;

Failure Unreachable(const std::string& path, const std::string& why) {
  return Failure{kExitUnreachable, "cannot reach the master at " + path + ": " + why +
                                       " (is radfarmd running? name its control socket with "
                                       "--control PATH or RADFARM_CONTROL)"};
}

Status SetTimeouts(int fd) {
  const timeval timeout{kControlTimeoutSeconds, 0};
  for (int option : {SO_RCVTIMEO, SO_SNDTIMEO}) {
    if (setsockopt(fd, SOL_SOCKET, option, &timeout, sizeof timeout) != 0) {
      return Error{std::string("setsockopt: ") + std::strerror(errno)};
    }
  }
  return Ok{};
}

}  // namespace

std::string DefaultControlPath() {
  const char* env = std::getenv("RADFARM_CONTROL");
  return env != nullptr && *env != '\0' ? env : kDefaultControlPath;
}

Failure MalformedResponse(const std::string& command, const std::string& why) {
  return Failure{kExitFailure, "malformed response from the master to '" + command + "': " + why};
}

int ExitCodeForErrorCode(std::string_view code) {
  if (code == "bad_request" || code == "not_found") return kExitBadInput;
  return kExitFailure;
}

Outcome<ControlClient> ControlClient::Connect(const std::string& socket_path) {
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  if (socket_path.empty() || socket_path.size() >= sizeof address.sun_path) {
    return Failure{kExitBadInput, "control socket path '" + socket_path + "': must be 1 to " +
                                      std::to_string(sizeof address.sun_path - 1) + " bytes"};
  }
  std::memcpy(address.sun_path, socket_path.data(), socket_path.size());
  UniqueFd fd(::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0));
  if (!fd.valid()) return Failure{kExitFailure, std::string("socket: ") + std::strerror(errno)};
  if (Status s = SetTimeouts(fd.get()); !s.ok()) return Failure{kExitFailure, s.error()};
  // No retry on EINTR: the connection would go on in the background. The CLI installs no signal
  // handlers, so it does not happen.
  if (::connect(fd.get(), reinterpret_cast<const sockaddr*>(&address), sizeof address) != 0) {
    const int error = errno;
    std::string why = std::strerror(error);
    if (error == EACCES || error == EPERM) {
      why += "; the socket is mode 0600, so run this as radfarmd's user (or root)";
    } else if (error == EAGAIN || error == EWOULDBLOCK) {
      why = "the master is not accepting connections (timed out)";
    }
    return Unreachable(socket_path, why);
  }
  return ControlClient(std::move(fd), socket_path);
}

Outcome<ControlReply> ControlClient::Call(json request, std::span<const uint8_t> attachment) {
  const std::string command = request.value("command", "");
  if (!attachment.empty()) request["attachment_bytes"] = attachment.size();
  std::string text;
  try {
    text = request.dump();
  } catch (const json::type_error&) {
    // Commands check their strings first (submit's --name); this is the net under them.
    return Failure{kExitBadInput, "'" + command +
                                      "' request: a text argument is not UTF-8; use UTF-8 "
                                      "characters or plain ASCII"};
  }
  if (text.size() > kMaxJsonFrameBytes) {
    return Failure{kExitBadInput, "'" + command + "' request is over the 1 MiB limit"};
  }
  const auto fail = [&](const std::string& why) {
    return Failure{kExitFailure, "control socket " + socket_path_ + ": " + why};
  };
  if (Status s = WriteFrame(fd_.get(),
                            std::span(reinterpret_cast<const uint8_t*>(text.data()), text.size()));
      !s.ok()) {
    return fail("sending '" + command + "': " + s.error());
  }
  if (!attachment.empty()) {
    if (Status s = WriteFrame(fd_.get(), attachment); !s.ok()) {
      return fail("sending the attachment of '" + command + "': " + s.error());
    }
  }
  return ReadReply(command);
}

Outcome<ControlReply> ControlClient::ReadReply(const std::string& command) {
  Result<std::vector<uint8_t>> frame = ReadFrame(fd_.get(), kMaxJsonFrameBytes);
  if (!frame.ok()) {
    return Failure{kExitFailure, "control socket " + socket_path_ + ": reading the answer to '" +
                                     command + "': " + frame.error()};
  }
  ControlReply reply;
  try {
    reply.body = json::parse(frame->begin(), frame->end());
  } catch (const json::parse_error& e) {
    return MalformedResponse(command, std::string("not JSON: ") + e.what());
  }
  const json& body = reply.body;
  if (!body.is_object()) return MalformedResponse(command, "not a JSON object");
  if (!body.contains("ok")) return MalformedResponse(command, "missing key 'ok'");
  if (!body["ok"].is_boolean()) return MalformedResponse(command, "'ok' is not a boolean");
  if (!body["ok"].get<bool>()) {
    for (const char* key : {"error", "code"}) {
      if (!body.contains(key))
        return MalformedResponse(command, std::string("missing key '") + key + "'");
      if (!body[key].is_string()) {
        return MalformedResponse(command, std::string("'") + key + "' is not a string");
      }
    }
    return Failure{ExitCodeForErrorCode(body["code"].get<std::string>()),
                   Printable(body["error"].get<std::string>())};
  }
  if (body.contains("attachment_bytes")) {
    const json& n = body["attachment_bytes"];
    if (!n.is_number_integer() || n.get<int64_t>() < 1 || n.get<int64_t>() > kMaxAttachmentBytes) {
      return MalformedResponse(command, "'attachment_bytes' is not an integer in 1.." +
                                            std::to_string(kMaxAttachmentBytes));
    }
    Result<std::vector<uint8_t>> data = ReadFrame(fd_.get(), n.get<uint32_t>());
    if (!data.ok()) {
      return Failure{kExitFailure, "control socket " + socket_path_ +
                                       ": reading the attachment of '" + command +
                                       "': " + data.error()};
    }
    if (data->size() != n.get<uint64_t>()) {
      return MalformedResponse(command, "'attachment_bytes' is " + n.dump() +
                                            " but the attachment has " +
                                            std::to_string(data->size()) + " bytes");
    }
    reply.attachment = std::move(*data);
  }
  return reply;
}

}  // namespace radfarm
