#include "daemon/console/web/web_routes.h"

#include <charconv>
#include <nlohmann/json.hpp>

#include "daemon/console/web/status_page.h"

namespace radfarm::web {
namespace {

using nlohmann::json;

WebResponse Reply(WebReply reply) { return WebResponse{std::move(reply), {}, false}; }

WebResponse Error(unsigned status, const std::string& message) {
  return Reply(JsonError(status, message));
}

WebResponse Unauthorized() {
  WebResponse r = Error(401, "this needs the farm's web token (docs/OPERATIONS.md)");
  r.headers.emplace_back("WWW-Authenticate", "Bearer realm=\"radfarm\"");
  return r;
}

WebResponse Asset(std::string_view body, const char* type) {
  return Reply({200, type, std::string(body)});
}

// "12" -> 12; anything else (signs, spaces, overflow, beyond 2^53) -> -1.
int64_t ParseId(std::string_view text) {
  int64_t id = -1;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), id);
  if (ec != std::errc() || end != text.data() + text.size() || text.empty() || id < 0 ||
      id > (int64_t{1} << 53)) {
    return -1;
  }
  return id;
}

}  // namespace

WebRoutes::WebRoutes(WebAccess access, const StatusBoard& board, WebHandlers handlers,
                     WebClock clock)
    : access_(std::move(access)),
      board_(board),
      handlers_(std::move(handlers)),
      clock_(std::move(clock)),
      failure_log_(std::make_unique<RateLimitedLog>("http", "refused web credentials",
                                                    kFailureLogLines, kFailureLogWindow)) {}

WebResponse WebRoutes::Handle(const WebRequest& request) const {
  if (!access_.HostAllowed(request.host)) {
    return Error(403, "the Host header must name a loopback address");
  }
  bool authenticated = false;
  const std::string_view credential = WebAccess::BearerOf(request.authorization);
  if (!credential.empty()) {
    if (std::optional<WebResponse> locked = LockedOut(request)) return std::move(*locked);
    authenticated = access_.BearerValid(request.authorization) ||
                    (access_.has_token() && sessions_->Use(credential, clock_()));
    if (!authenticated) return Refused(request, "a wrong token or an ended session");
  }
  const std::string_view path = request.path;
  const bool get = request.method == "GET" || request.method == "HEAD";
  if (get && (path == "/" || path == "/index.html")) {
    return Asset(StatusPageHtml(), "text/html; charset=utf-8");
  }
  if (get && path == "/status.js") return Asset(StatusPageJs(), "text/javascript; charset=utf-8");
  if (get && path == "/status.css") return Asset(StatusPageCss(), "text/css; charset=utf-8");
  if (path == "/api/session") {
    if (request.method == "POST") return Login(request);
    if (request.method == "DELETE") return Logout(request);
    if (get) return Session(authenticated);
    return Error(405, "GET, POST or DELETE");
  }
  constexpr std::string_view kJobs = "/api/jobs/";
  if (path.substr(0, kJobs.size()) == kJobs) {
    return JobRoute(request, path.substr(kJobs.size()), authenticated);
  }
  const bool data = path == "/api/status" || path == "/api/events" || path == "/metrics";
  if (!data) return Error(404, "no such page");
  if (!get) return Error(405, "GET only");
  if (!access_.MayRead(authenticated)) return Unauthorized();
  if (path == "/api/events") return WebResponse{{200, "text/event-stream", ""}, {}, true};
  const auto snapshot = board_.Latest();
  if (!snapshot) return Error(503, "no status yet: the master is starting");
  if (path == "/metrics") {
    return Reply({200, "text/plain; version=0.0.4; charset=utf-8", snapshot->metrics_text});
  }
  return Reply({200, "application/json", snapshot->status_json});
}

WebResponse WebRoutes::Session(bool authenticated) const {
  return Reply({200, "application/json",
                json{{"ok", true},
                     {"authenticated", authenticated},
                     {"read", access_.MayRead(authenticated)},
                     {"act", access_.MayAct(authenticated)},
                     {"token", access_.has_token()},
                     {"loopback", access_.loopback()}}
                    .dump()});
}

WebResponse WebRoutes::Login(const WebRequest& request) const {
  if (!access_.has_token()) {
    return Error(403, "this master has no web token: start radfarmd with --http-token-file");
  }
  // Only the page (or a script) sends the header; a form on another site cannot.
  if (!request.marked) return Error(403, "the X-Radfarm-Request header is missing");
  const json body = json::parse(request.body, nullptr, false);
  if (body.is_discarded() || !body.is_object() || !body.contains("token") ||
      !body["token"].is_string()) {
    return Error(400, "expected {\"token\": \"...\"}");
  }
  if (std::optional<WebResponse> locked = LockedOut(request)) return std::move(*locked);
  if (!access_.TokenMatches(body["token"].get<std::string>())) {
    return Refused(request, "a wrong token signing in");
  }
  guard_->Succeeded(request.client);
  const std::string session = sessions_->Begin(clock_());
  return Reply({200, "application/json",
                json{{"ok", true},
                     {"session", session},
                     {"idle_seconds", std::chrono::seconds(SessionTable::kIdle).count()},
                     {"max_age_seconds", std::chrono::seconds(SessionTable::kMaxAge).count()}}
                    .dump()});
}

WebResponse WebRoutes::Logout(const WebRequest& request) const {
  // Handle has already refused a session that is not live.
  const std::string_view session = WebAccess::BearerOf(request.authorization);
  if (session.empty()) return Error(400, "sign out with \"Authorization: Bearer SESSION\"");
  const bool ended = sessions_->End(session, clock_());
  return Reply({200, "application/json", json{{"ok", true}, {"ended", ended}}.dump()});
}

WebResponse WebRoutes::Refused(const WebRequest& request, const char* what) const {
  const uint32_t failures = guard_->Failed(request.client, clock_());
  // Never the credential itself: log lines end up in bug reports.
  failure_log_->Warn(request.client + ": refused " + what + " (" + std::to_string(failures) +
                     " in a row from this address)");
  return Unauthorized();
}

std::optional<WebResponse> WebRoutes::LockedOut(const WebRequest& request) const {
  const auto wait = guard_->LockedFor(request.client, clock_());
  if (wait <= SignInGuard::Duration::zero()) return std::nullopt;
  const auto seconds = std::chrono::ceil<std::chrono::seconds>(wait).count();
  WebResponse r = Error(429, "too many wrong tokens from this address: try again in " +
                                 std::to_string(seconds) + " s");
  r.headers.emplace_back("Retry-After", std::to_string(seconds));
  return r;
}

WebResponse WebRoutes::JobRoute(const WebRequest& request, std::string_view rest,
                                bool authenticated) const {
  const size_t slash = rest.find('/');
  const int64_t id = ParseId(rest.substr(0, slash));
  if (slash == std::string_view::npos || id < 0) return Error(404, "no such page");
  const std::string_view what = rest.substr(slash + 1);
  if (what == "preview.png") {
    if (request.method != "GET" && request.method != "HEAD") return Error(405, "GET only");
    if (!access_.MayRead(authenticated)) return Unauthorized();
    return Reply(handlers_.preview(id, request.connection_fd));
  }
  if (what != "pause" && what != "resume" && what != "cancel") return Error(404, "no such page");
  if (request.method != "POST") return Error(405, "POST only");
  if (!access_.has_token()) {
    return Error(403, "actions need a web token: start radfarmd with --http-token-file");
  }
  // Only an Authorization header authenticates, which no other page can make a browser send.
  if (!authenticated) return Unauthorized();
  return Reply(handlers_.act(what, id));
}

}  // namespace radfarm::web
