// RawAgent: a blocking socket that passes the real agent handshake (ProtocolSession::ForAgent)
// and then does what no radfarm-agent does: stays silent, or sends raw bytes such as a frame's
// length prefix and part of its payload (an agent's credential in a hostile hand).
#pragma once

#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "protocol/farm_secret.h"

namespace radfarm::testing {

class RawAgent {
 public:
  // Connects to `host_port` ("127.0.0.1:PORT") and runs the handshake as `name`.
  RawAgent(const std::string& host_port, const protocol::FarmSecret& secret,
           const std::string& name);
  ~RawAgent();
  RawAgent(const RawAgent&) = delete;
  RawAgent& operator=(const RawAgent&) = delete;

  // Whether the master's Welcome came (the handshake passed).
  bool welcomed() const { return welcomed_; }
  // Reads the master's next frame: the detail of its Close, if that is what it is (a refusal
  // comes right after the Welcome); nullopt if another frame came, or none within `timeout`.
  std::optional<std::string> ReadClose(std::chrono::milliseconds timeout);
  // Writes all of `bytes` (blocking); false once the master has closed the connection.
  bool SendAll(std::string_view bytes);
  // Waits until the master closes the connection (true) or `timeout` passes.
  bool WaitForClose(std::chrono::milliseconds timeout);

 private:
  int fd_ = -1;
  bool welcomed_ = false;
  struct Session;
  std::unique_ptr<Session> session_;
};

}  // namespace radfarm::testing
