// ControlServer: the master's control socket (docs/CONTROL.md): a 0600 Unix socket in the state
// directory, frames of JSON (plus one binary attachment after a request or response that says
// "attachment_bytes"). It parses and checks each request, hands it to the master, and writes the
// answer. One request at a time per connection; a malformed frame or JSON gets an error response
// and the connection is closed. Loop thread only.
//
// Limits as bytes arrive: a frame's length is checked when its prefix is in, against 1 MiB for a
// JSON request and exactly the announced attachment_bytes for the attachment that follows, so a
// client cannot make the daemon buffer more than it may send. A client has request_timeout to
// send each whole request, its attachment included (the clock stops while the daemon works on an
// answer and starts again when it is sent): idle clients, and clients that announce an attachment
// and never send it, are closed with a log line.
#pragma once

#include <chrono>
#include <functional>
#include <map>
#include <memory>
#include <string>

#include "base/result.h"
#include "daemon/control/control_request_parser.h"
#include "daemon/control/control_types.h"
#include "loop/event_loop.h"
#include "loop/framed_connection.h"
#include "loop/timer.h"
#include "loop/unix_listener.h"

namespace radfarm::daemon {

struct ControlServerOptions {
  std::chrono::milliseconds request_timeout{60000};
};

class ControlServer {
 public:
  using Handler = std::function<void(ControlRequest, ControlRespond)>;

  static Result<std::unique_ptr<ControlServer>> Listen(loop::EventLoop& loop,
                                                       const std::string& path, Handler handler,
                                                       ControlServerOptions options = {});
  ControlServer(const ControlServer&) = delete;
  ControlServer& operator=(const ControlServer&) = delete;
  ~ControlServer();

  const std::string& path() const { return listener_->path(); }
  void Close();

 private:
  struct Client;
  ControlServer(loop::EventLoop& loop, Handler handler, ControlServerOptions options);
  void OnConnection(std::unique_ptr<loop::FramedConnection> connection);
  void OnFrame(Client& client, std::span<const uint8_t> payload);
  void Dispatch(Client& client, ControlRequest request);
  void Reply(uint64_t client_id, ControlResponse response);
  void Refuse(Client& client, const std::string& code, const std::string& message);
  void OnClosed(uint64_t client_id, const std::string& reason);
  // Gives the client request_timeout to send its next whole request.
  void StartRequestClock(Client& client);

  loop::EventLoop& loop_;
  Handler handler_;
  const ControlServerOptions options_;
  std::unique_ptr<loop::UnixListener> listener_;
  std::map<uint64_t, std::unique_ptr<Client>> clients_;
  uint64_t next_client_ = 1;
};

}  // namespace radfarm::daemon
