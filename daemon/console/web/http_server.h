// HttpServer: the web console's HTTP listener, libmicrohttpd running its own threads (one polls
// the listening socket, one per connection), so nothing here ever runs on or blocks the master's
// event loop. Each request is parsed into a WebRequest, answered by WebRoutes, and written back;
// an event stream (GET /api/events) reads the StatusBoard on its connection's thread.
//
// Threads: Start and Stop on the loop thread. Stop joins the HTTP threads; before it, close the
// StatusBoard (ends the event streams) and the LoopCaller (ends the waits on the loop), or Stop
// would wait for them. At most kMaxConnections connections (kMaxPerAddress per client address).
// libmicrohttpd's warnings (two per malformed request) are logged at most kLogLines per window,
// the rest counted in a summary line (rate_limited_log.h).
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <string>

#include "base/result.h"
#include "daemon/console/web/rate_limited_log.h"
#include "daemon/console/web/status_board.h"
#include "daemon/console/web/web_routes.h"
#include "loop/host_port.h"

struct MHD_Daemon;

namespace radfarm::web {

class HttpServer {
 public:
  static constexpr unsigned kMaxConnections = 64;
  static constexpr unsigned kMaxPerAddress = 16;
  static constexpr uint32_t kLogLines = 20;
  static constexpr std::chrono::seconds kLogWindow{10};

  // Binds `address` (an IP literal or a name; port 0 picks a free port) and starts serving.
  static Result<std::unique_ptr<HttpServer>> Start(const loop::HostPort& address,
                                                   std::unique_ptr<WebRoutes> routes,
                                                   const StatusBoard& board,
                                                   std::chrono::seconds log_window = kLogWindow);
  ~HttpServer();  // Stop()
  HttpServer(const HttpServer&) = delete;
  HttpServer& operator=(const HttpServer&) = delete;

  // "HOST:PORT" as bound (the port filled in).
  const std::string& address() const { return address_; }
  void Stop();

 private:
  HttpServer(std::unique_ptr<WebRoutes> routes, const StatusBoard& board,
             std::chrono::seconds log_window);

  std::unique_ptr<WebRoutes> routes_;
  const StatusBoard& board_;
  RateLimitedLog server_log_;
  MHD_Daemon* daemon_ = nullptr;
  std::string address_;

  friend struct HttpGlue;
};

}  // namespace radfarm::web
