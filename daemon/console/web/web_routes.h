// WebRoutes: the web console's URLs, its access rules applied (web_access.h), as a function from
// a parsed request to a response, with no sockets, so it is tested alone (HttpServer is the glue
// to libmicrohttpd).
//
//   GET  /, /status.js, /status.css      the page (no data in it: it reads the API)
//   GET  /api/session                    what this browser may do: {"read", "act", "token", ...}
//   POST /api/session {"token": T}       trades the token for a session cookie
//   GET  /api/status                     the latest StatusSnapshot's JSON
//   GET  /api/events                     server-sent events: each new snapshot (event_stream.h)
//   GET  /api/jobs/ID/preview.png        the image of the job's latest checkpoint
//   POST /api/jobs/ID/{pause,resume,cancel}  as `radfarm pause ID`..., through the control code
//   GET  /metrics                        Prometheus text (metrics_text.h)
//
// Threads: Handle on any HTTP thread; it may block in a handler (WebHandlers) or not at all.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "daemon/console/web/status_board.h"
#include "daemon/console/web/web_access.h"
#include "daemon/console/web/web_reply.h"

namespace radfarm::web {

struct WebRequest {
  std::string method;                       // "GET", "POST", ...
  std::string path;                         // without the query
  std::string host, authorization, cookie;  // headers ("" when absent)
  bool marked = false;                      // the X-Radfarm-Request header is present
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
  // A PNG of job `id`'s latest checkpoint.
  std::function<WebReply(int64_t id)> preview;
};

class WebRoutes {
 public:
  WebRoutes(WebAccess access, const StatusBoard& board, WebHandlers handlers);

  WebResponse Handle(const WebRequest& request) const;

 private:
  WebResponse Session(const WebRequest& request, bool authenticated) const;
  WebResponse Login(const WebRequest& request) const;
  WebResponse JobRoute(const WebRequest& request, std::string_view rest, bool authenticated) const;

  WebAccess access_;
  const StatusBoard& board_;
  WebHandlers handlers_;
};

}  // namespace radfarm::web
