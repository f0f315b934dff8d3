// A scripted stand-in for radfarmd's control socket (docs/CONTROL.md), for tests that run the real
// radfarm binary: a thread serving a Unix socket in a temporary directory. It reads each request
// frame (and the attachment frame after it when the request announces attachment_bytes), records
// it, and sends whatever the test's handler returns, which may be deliberately malformed.
//
// The framing code here is written separately from cli/control_frames.cc on purpose: a mistake
// shared by both sides would go unnoticed.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "testing/child_process.h"
#include "testing/temp_dir.h"

namespace radfarm::testing {

struct ControlRequest {
  nlohmann::json body;
  std::vector<uint8_t> attachment;
};

struct ControlAnswer {
  nlohmann::json body;              // sent as one frame (ignored when `raw` is set)
  std::vector<uint8_t> attachment;  // non-empty: announced as attachment_bytes and sent after
  std::optional<std::string> raw;   // bytes to send as they are, with no framing added
  bool close = false;               // close the connection after sending (or instead of answering)
};

// {"ok": true} plus `fields`.
ControlAnswer OkAnswer(nlohmann::json fields = nlohmann::json::object());
// {"ok": false, "error": message, "code": code}.
ControlAnswer ErrorAnswer(const std::string& code, const std::string& message);
// One frame holding `payload` as it is (not JSON, say).
std::string Frame(const std::string& payload);

// A Unix stream socket bound to DIR/control.sock; listening unless `listen` is false (connecting
// to it is then refused, as to a dead daemon's leftover socket).
class UnixListener {
 public:
  explicit UnixListener(const TempDir& dir, bool listen = true);
  ~UnixListener();
  UnixListener(const UnixListener&) = delete;
  UnixListener& operator=(const UnixListener&) = delete;

  const std::string& path() const { return path_; }
  int fd() const { return fd_; }
  // True when a client has connected (accepted or still waiting in the backlog).
  bool HasPendingConnection() const;

 private:
  std::string path_;
  int fd_ = -1;
};

class FakeControlServer {
 public:
  using Handler = std::function<ControlAnswer(const ControlRequest&)>;

  // `handler` runs on the server's thread, once per request, in order.
  explicit FakeControlServer(Handler handler);
  // Stops the thread, closing any open connection.
  ~FakeControlServer();
  FakeControlServer(const FakeControlServer&) = delete;
  FakeControlServer& operator=(const FakeControlServer&) = delete;

  const std::string& socket_path() const { return listener_.path(); }
  std::vector<ControlRequest> requests() const;
  int connections() const;

 private:
  void Serve();
  void ServeConnection(int fd);
  // Reads exactly `size` bytes unless the peer closes or the server stops.
  bool ReadExact(int fd, uint8_t* data, size_t size);
  bool ReadFrame(int fd, std::vector<uint8_t>* payload);

  TempDir dir_;
  UnixListener listener_;
  Handler handler_;
  int wake_[2] = {-1, -1};  // a pipe: writing to it stops the thread
  mutable std::mutex mutex_;
  std::vector<ControlRequest> requests_;
  int connections_ = 0;
  std::thread thread_;
};

// A handler that gives every request the same answer.
FakeControlServer::Handler Always(ControlAnswer answer);

}  // namespace radfarm::testing
