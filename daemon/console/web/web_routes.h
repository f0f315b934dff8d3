// WebRoutes: the web console's URLs, its access rules applied (web_access.h), as a function from
// a parsed request to a response, with no sockets, so it is tested alone (HttpServer is the glue
// to libmicrohttpd).
//
//   GET  /, /status.js, /status.css      the page (no data in it: it reads the API)
//   GET  /api/session                    what this browser may do: {"read", "act", "token", ...}
//   POST /api/session {"token": T}       trades the token for a new session: {"session": S, ...}
//   DELETE /api/session                  signs out: ends the session its Authorization names
//   GET  /api/status                     the latest StatusSnapshot's JSON
//   GET  /api/events                     server-sent events: each new snapshot (event_stream.h)
//   GET  /api/jobs/ID/preview.png        the image of the job's latest checkpoint
//   POST /api/jobs/ID/{pause,resume,cancel}  as `radfarm pause ID`..., through the control code
//   GET  /metrics                        Prometheus text (metrics_text.h)
//
// Credentials come only in "Authorization: Bearer X", X the web token or a session
// (session_table.h). A wrong one, or a wrong token signing in, counts against the client's
// address (sign_in_guard.h), which is then answered 429 for a while, and is logged (at most
// kFailureLogLines lines per kFailureLogWindow).
//
// Threads: Handle on any HTTP thread; it may block in a handler (WebHandlers) or not at all.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "daemon/console/web/rate_limited_log.h"
#include "daemon/console/web/session_table.h"
#include "daemon/console/web/sign_in_guard.h"
#include "daemon/console/web/status_board.h"
#include "daemon/console/web/web_access.h"
#include "daemon/console/web/web_reply.h"

namespace radfarm::web {

struct WebRequest {
  std::string method;               // "GET", "POST", ...
  std::string path;                 // without the query
  std::string host, authorization;  // headers ("" when absent)
  bool marked = false;              // the X-Radfarm-Request header is present
  std::string client;               // the client's IP address
  int connection_fd = -1;           // the client's socket, to see it leave (-1: unknown)
  std::string body;
};

struct WebResponse {
  WebReply reply;
  std::vector<std::pair<std::string, std::string>> headers;
  bool event_stream = false;  // the body is an EventStream on the board, not reply.body
};

// What the master does for the routes, called on the HTTP thread (they may block).
struct WebHandlers {
  // "pause", "resume" or "cancel" of job `id`.
  std::function<WebReply(std::string_view action, int64_t id)> act;
  // A PNG of job `id`'s latest checkpoint; `connection_fd` as in WebRequest: a wait for it ends
  // when the client goes.
  std::function<WebReply(int64_t id, int connection_fd)> preview;
};

// The time sessions and lockouts are measured in; tests pass a fake one.
using WebClock = std::function<std::chrono::steady_clock::time_point()>;

class WebRoutes {
 public:
  static constexpr uint32_t kFailureLogLines = 10;
  static constexpr std::chrono::seconds kFailureLogWindow{60};

  WebRoutes(WebAccess access, const StatusBoard& board, WebHandlers handlers,
            WebClock clock = std::chrono::steady_clock::now);

  WebResponse Handle(const WebRequest& request) const;

 private:
  WebResponse Session(bool authenticated) const;
  WebResponse Login(const WebRequest& request) const;
  WebResponse Logout(const WebRequest& request) const;
  WebResponse JobRoute(const WebRequest& request, std::string_view rest, bool authenticated) const;
  // A refused credential from `request.client`: counted, logged, and the answer to give.
  WebResponse Refused(const WebRequest& request, const char* what) const;
  // 429 while the client is locked out; nullopt when it may try.
  std::optional<WebResponse> LockedOut(const WebRequest& request) const;

  WebAccess access_;
  const StatusBoard& board_;
  WebHandlers handlers_;
  WebClock clock_;
  // Shared by the HTTP threads, each thread-safe; held by pointer so WebRoutes can move.
  std::unique_ptr<SessionTable> sessions_ = std::make_unique<SessionTable>();
  std::unique_ptr<SignInGuard> guard_ = std::make_unique<SignInGuard>();
  std::unique_ptr<RateLimitedLog> failure_log_;
};

}  // namespace radfarm::web
