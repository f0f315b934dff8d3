#include "daemon/console/web/web_routes.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "loop/log.h"

namespace radfarm::web {
namespace {

const std::string kRoutesToken = "0123456789abcdef0123";

class WebRoutesTest : public ::testing::Test {
 protected:
  WebRoutes Routes(bool loopback, const std::string& token) {
    WebHandlers handlers;
    handlers.act = [this](std::string_view action, int64_t id) {
      acted.push_back(std::string(action) + " " + std::to_string(id));
      return WebReply{200, "application/json", R"({"ok":true})"};
    };
    handlers.preview = [](int64_t id, int) {
      return WebReply{200, "image/png", "png of " + std::to_string(id)};
    };
    return WebRoutes(WebAccess(loopback, token), board, handlers, [this] { return now; });
  }
  static WebRequest Get(const std::string& path) {
    WebRequest r;
    r.method = "GET";
    r.path = path;
    r.host = "127.0.0.1:8080";
    r.client = "127.0.0.1";
    return r;
  }
  static WebRequest Post(const std::string& path) {
    WebRequest r = Get(path);
    r.method = "POST";
    return r;
  }

  // Signs in with `token`; returns the answer's session ("" when refused).
  static std::string SignIn(const WebRoutes& routes, const std::string& token,
                            const std::string& client = "127.0.0.1") {
    WebRequest login = Post("/api/session");
    login.marked = true;
    login.client = client;
    login.body = nlohmann::json{{"token", token}}.dump();
    const WebResponse r = routes.Handle(login);
    if (r.reply.status != 200) return "";
    return nlohmann::json::parse(r.reply.body).value("session", "");
  }
  static WebRequest WithSession(WebRequest r, const std::string& session) {
    r.authorization = "Bearer " + session;
    return r;
  }

  StatusBoard board;
  std::vector<std::string> acted;
  std::chrono::steady_clock::time_point now{};
};

TEST_F(WebRoutesTest, ThePageAndItsFilesAreServed) {
  WebRoutes routes = Routes(true, "");
  const WebResponse page = routes.Handle(Get("/"));
  EXPECT_EQ(page.reply.status, 200u);
  EXPECT_EQ(page.reply.content_type, "text/html; charset=utf-8");
  EXPECT_NE(page.reply.body.find("<table id=\"jobs\">"), std::string::npos);
  EXPECT_NE(routes.Handle(Get("/status.js")).reply.body.find("sessionStorage"), std::string::npos);
  EXPECT_EQ(routes.Handle(Get("/status.css")).reply.status, 200u);
  EXPECT_EQ(routes.Handle(Get("/nothing")).reply.status, 404u);
}

TEST_F(WebRoutesTest, StatusAndMetricsComeFromTheLatestSnapshot) {
  WebRoutes routes = Routes(true, "");
  EXPECT_EQ(routes.Handle(Get("/api/status")).reply.status, 503u);  // nothing published yet
  StatusSnapshot s;
  s.status_json = R"({"jobs":[]})";
  s.metrics_text = "radfarm_jobs{state=\"done\"} 0\n";
  board.Publish(s);
  EXPECT_EQ(routes.Handle(Get("/api/status")).reply.body, s.status_json);
  const WebResponse metrics = routes.Handle(Get("/metrics"));
  EXPECT_EQ(metrics.reply.body, s.metrics_text);
  EXPECT_EQ(metrics.reply.content_type, "text/plain; version=0.0.4; charset=utf-8");
  EXPECT_TRUE(routes.Handle(Get("/api/events")).event_stream);
  EXPECT_EQ(routes.Handle(Post("/metrics")).reply.status, 405u);
}

TEST_F(WebRoutesTest, ARequestForAnotherHostNameIsRefusedOnLoopback) {
  WebRoutes routes = Routes(true, kRoutesToken);
  WebRequest r = Get("/api/session");
  r.host = "rebound.example:8080";
  EXPECT_EQ(routes.Handle(r).reply.status, 403u);
}

TEST_F(WebRoutesTest, OffLoopbackEveryDataRouteNeedsTheToken) {
  WebRoutes routes = Routes(false, kRoutesToken);
  board.Publish(StatusSnapshot{});
  for (const char* path : {"/api/status", "/api/events", "/metrics", "/api/jobs/1/preview.png"}) {
    const WebResponse denied = routes.Handle(Get(path));
    EXPECT_EQ(denied.reply.status, 401u) << path;
    EXPECT_FALSE(denied.event_stream);
    WebRequest with = Get(path);
    with.authorization = "Bearer " + kRoutesToken;
    EXPECT_EQ(routes.Handle(with).reply.status, 200u) << path;
  }
  EXPECT_EQ(routes.Handle(Get("/")).reply.status, 200u);  // the page itself holds no data
}

TEST_F(WebRoutesTest, WithoutATokenThePageIsReadOnly) {
  WebRoutes routes = Routes(true, "");
  WebRequest r = Post("/api/jobs/3/pause");
  r.marked = true;
  EXPECT_EQ(routes.Handle(r).reply.status, 403u);
  EXPECT_TRUE(acted.empty());
  const auto session = nlohmann::json::parse(routes.Handle(Get("/api/session")).reply.body);
  EXPECT_TRUE(session["read"].get<bool>());
  EXPECT_FALSE(session["act"].get<bool>());
}

TEST_F(WebRoutesTest, ActionsNeedTheTokenOrASessionInTheAuthorizationHeader) {
  WebRoutes routes = Routes(true, kRoutesToken);
  WebRequest anonymous = Post("/api/jobs/3/pause");
  anonymous.marked = true;
  EXPECT_EQ(routes.Handle(anonymous).reply.status, 401u);

  EXPECT_EQ(SignIn(routes, "wrong-wrong-wrong-wrong"), "");
  WebRequest login = Post("/api/session");
  login.marked = true;
  login.body = nlohmann::json{{"token", kRoutesToken}}.dump();
  const WebResponse signed_in = routes.Handle(login);
  ASSERT_EQ(signed_in.reply.status, 200u);
  // No cookie: a browser would hand one to every other port of this host.
  EXPECT_TRUE(signed_in.headers.empty());
  const std::string session = nlohmann::json::parse(signed_in.reply.body)["session"];
  EXPECT_EQ(session.find(kRoutesToken), std::string::npos);  // the session is not the token

  WebRequest page = WithSession(Post("/api/jobs/3/cancel"), session);
  EXPECT_EQ(routes.Handle(page).reply.status, 200u);
  const auto state =
      nlohmann::json::parse(routes.Handle(WithSession(Get("/api/session"), session)).reply.body);
  EXPECT_TRUE(state["act"].get<bool>());
  WebRequest script = WithSession(Post("/api/jobs/4/resume"), kRoutesToken);
  EXPECT_EQ(routes.Handle(script).reply.status, 200u);
  EXPECT_EQ(acted, (std::vector<std::string>{"cancel 3", "resume 4"}));
}

TEST_F(WebRoutesTest, EachSignInHasItsOwnSessionAndSigningOutEndsIt) {
  WebRoutes routes = Routes(true, kRoutesToken);
  const std::string first = SignIn(routes, kRoutesToken);
  const std::string second = SignIn(routes, kRoutesToken);
  ASSERT_FALSE(first.empty());
  EXPECT_NE(first, second);
  WebRequest logout = WithSession(Get("/api/session"), first);
  logout.method = "DELETE";
  ASSERT_EQ(routes.Handle(logout).reply.status, 200u);
  EXPECT_EQ(routes.Handle(WithSession(Post("/api/jobs/3/pause"), first)).reply.status, 401u);
  EXPECT_EQ(routes.Handle(WithSession(Post("/api/jobs/3/pause"), second)).reply.status, 200u);
  EXPECT_EQ(acted, (std::vector<std::string>{"pause 3"}));
}

TEST_F(WebRoutesTest, ASessionExpiresWhenIdleAndAtItsMaximumAge) {
  WebRoutes routes = Routes(false, kRoutesToken);
  board.Publish(StatusSnapshot{});
  const std::string idle = SignIn(routes, kRoutesToken);
  now += SessionTable::kIdle;
  EXPECT_EQ(routes.Handle(WithSession(Get("/api/status"), idle)).reply.status, 401u);

  const std::string busy = SignIn(routes, kRoutesToken);
  const auto began = now;
  while (now + SessionTable::kIdle / 2 < began + SessionTable::kMaxAge) {
    now += SessionTable::kIdle / 2;
    ASSERT_EQ(routes.Handle(WithSession(Get("/api/status"), busy)).reply.status, 200u);
  }
  now = began + SessionTable::kMaxAge;
  EXPECT_EQ(routes.Handle(WithSession(Get("/api/status"), busy)).reply.status, 401u);
}

TEST_F(WebRoutesTest, WrongTokensAreLoggedAndLockTheirAddressOutWithoutSlowingOthers) {
  std::vector<std::string> lines;
  loop::SetLogSink([&](std::string_view line) { lines.emplace_back(line); });
  WebRoutes routes = Routes(true, kRoutesToken);
  for (uint32_t i = 0; i <= SignInGuard::kFreeFailures; ++i) {
    EXPECT_EQ(SignIn(routes, "guess-guess-guess-" + std::to_string(i), "10.1.1.1"), "");
  }
  WebRequest locked = Post("/api/session");
  locked.marked = true;
  locked.client = "10.1.1.1";
  locked.body = nlohmann::json{{"token", kRoutesToken}}.dump();
  const WebResponse refused = routes.Handle(locked);
  EXPECT_EQ(refused.reply.status, 429u);  // even the right token, until the lockout ends
  ASSERT_EQ(refused.headers.size(), 1u);
  EXPECT_EQ(refused.headers[0].first, "Retry-After");
  // A bearer header is a guess too.
  EXPECT_EQ(routes.Handle(WithSession(Post("/api/jobs/1/pause"), kRoutesToken)).reply.status, 200u);
  WebRequest guess = WithSession(Post("/api/jobs/1/pause"), kRoutesToken);
  guess.client = "10.1.1.1";
  EXPECT_EQ(routes.Handle(guess).reply.status, 429u);
  EXPECT_FALSE(SignIn(routes, kRoutesToken, "10.2.2.2").empty());  // others are not slowed
  now += SignInGuard::kFirstLockout;
  EXPECT_FALSE(SignIn(routes, kRoutesToken, "10.1.1.1").empty());
  loop::SetLogSink({});
  size_t logged = 0;
  for (const std::string& line : lines) {
    if (line.find("10.1.1.1: refused a wrong token signing in") != std::string::npos) ++logged;
    EXPECT_EQ(line.find("guess-guess"), std::string::npos) << line;  // never the guess itself
  }
  EXPECT_EQ(logged, SignInGuard::kFreeFailures + 1);
}

TEST_F(WebRoutesTest, JobRoutesCheckTheIdActionAndMethod) {
  WebRoutes routes = Routes(true, kRoutesToken);
  WebRequest r = Post("/api/jobs/3/delete");
  r.authorization = "Bearer " + kRoutesToken;
  EXPECT_EQ(routes.Handle(r).reply.status, 404u);
  for (const char* bad : {"/api/jobs/-1/pause", "/api/jobs/x/pause", "/api/jobs/1x/pause",
                          "/api/jobs/99999999999999999999/pause", "/api/jobs//pause"}) {
    r.path = bad;
    EXPECT_EQ(routes.Handle(r).reply.status, 404u) << bad;
  }
  EXPECT_EQ(routes.Handle(Get("/api/jobs/3/pause")).reply.status, 405u);
  EXPECT_EQ(routes.Handle(Get("/api/jobs/7/preview.png")).reply.body, "png of 7");
  EXPECT_TRUE(acted.empty());
}

}  // namespace
}  // namespace radfarm::web
