// HttpServer: the web console's HTTP listener, libmicrohttpd running its own threads (one polls
// the listening socket, one per connection), so nothing here ever runs on or blocks the master's
// event loop. Each request is parsed into a WebRequest, answered by WebRoutes, and written back;
// an event stream (GET /api/events) reads the StatusBoard on its connection's thread.
//
// Threads: Start and Stop on the loop thread. Stop joins the HTTP threads; before it, close the
// StatusBoard (ends the event streams) and the LoopCaller (ends the waits on the loop), or Stop
// would wait for them.
//
// Slow and many clients: at most kMaxConnections connections (threads). A connection waiting
// for its request has a total deadline and a capped number of peers, the oldest going first
// (connection_deadlines.h); a reaper thread shuts the sockets of those past it. Event streams are
// capped in all and per address, a new one evicting the oldest (stream_slots.h).
// libmicrohttpd's warnings (two per malformed request) are logged at most kLogLines per window,
// the rest counted in a summary line (rate_limited_log.h).
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "base/result.h"
#include "daemon/console/web/connection_deadlines.h"
#include "daemon/console/web/rate_limited_log.h"
#include "daemon/console/web/status_board.h"
#include "daemon/console/web/stream_slots.h"
#include "daemon/console/web/web_routes.h"
#include "loop/host_port.h"

struct MHD_Daemon;

namespace radfarm::web {

// What slow and many clients may hold (HttpServer).
struct HttpLimits {
  // From a connection's start (or its last response) to its whole next request.
  std::chrono::milliseconds request_deadline = std::chrono::seconds(10);
  size_t max_waiting = 64;              // connections waiting for their request
  size_t max_waiting_per_address = 16;  // of them from one client address
  size_t max_event_streams = 16;
  size_t max_event_streams_per_address = 8;
  std::chrono::seconds log_window{10};  // for the kLogLines of libmicrohttpd's warnings
};

class HttpServer {
 public:
  static constexpr unsigned kMaxConnections = 256;  // a backstop: HttpLimits binds first
  static constexpr uint32_t kLogLines = 20;

  using Limits = HttpLimits;

  // Binds `address` (an IP literal or a name; port 0 picks a free port) and starts serving.
  static Result<std::unique_ptr<HttpServer>> Start(const loop::HostPort& address,
                                                   std::unique_ptr<WebRoutes> routes,
                                                   const StatusBoard& board, Limits limits = {});
  ~HttpServer();  // Stop()
  HttpServer(const HttpServer&) = delete;
  HttpServer& operator=(const HttpServer&) = delete;

  // "HOST:PORT" as bound (the port filled in).
  const std::string& address() const { return address_; }
  void Stop();

 private:
  HttpServer(std::unique_ptr<WebRoutes> routes, const StatusBoard& board, const Limits& limits);

  // Shuts `fds` (under deadlines_mutex_, so none has been closed yet); their threads end.
  static void Shut(const std::vector<int>& fds);
  // The reaper thread: shuts connections past their deadline until Stop.
  void Reap();

  std::unique_ptr<WebRoutes> routes_;
  const StatusBoard& board_;
  const Limits limits_;
  RateLimitedLog server_log_;
  StreamSlots streams_;
  std::mutex deadlines_mutex_;
  ConnectionDeadlines deadlines_;
  std::condition_variable reaper_wake_;
  bool stopping_ = false;  // under deadlines_mutex_
  std::thread reaper_;
  MHD_Daemon* daemon_ = nullptr;
  std::string address_;

  friend struct HttpGlue;
};

}  // namespace radfarm::web
