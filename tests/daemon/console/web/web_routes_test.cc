#include "daemon/console/web/web_routes.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

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
    handlers.preview = [](int64_t id) {
      return WebReply{200, "image/png", "png of " + std::to_string(id)};
    };
    return WebRoutes(WebAccess(loopback, token), board, handlers);
  }
  static WebRequest Get(const std::string& path) {
    WebRequest r;
    r.method = "GET";
    r.path = path;
    r.host = "127.0.0.1:8080";
    return r;
  }
  static WebRequest Post(const std::string& path) {
    WebRequest r = Get(path);
    r.method = "POST";
    return r;
  }

  StatusBoard board;
  std::vector<std::string> acted;
};

TEST_F(WebRoutesTest, ThePageAndItsFilesAreServed) {
  WebRoutes routes = Routes(true, "");
  const WebResponse page = routes.Handle(Get("/"));
  EXPECT_EQ(page.reply.status, 200u);
  EXPECT_EQ(page.reply.content_type, "text/html; charset=utf-8");
  EXPECT_NE(page.reply.body.find("<table id=\"jobs\">"), std::string::npos);
  EXPECT_NE(routes.Handle(Get("/status.js")).reply.body.find("EventSource"), std::string::npos);
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

TEST_F(WebRoutesTest, ActionsNeedTheTokenAndWithACookieTheRequestHeader) {
  WebRoutes routes = Routes(true, kRoutesToken);
  WebRequest anonymous = Post("/api/jobs/3/pause");
  anonymous.marked = true;
  EXPECT_EQ(routes.Handle(anonymous).reply.status, 401u);

  WebRequest login = Post("/api/session");
  login.marked = true;
  login.body = R"({"token":"wrong-wrong-wrong-wrong"})";
  EXPECT_EQ(routes.Handle(login).reply.status, 401u);
  login.body = nlohmann::json{{"token", kRoutesToken}}.dump();
  const WebResponse signed_in = routes.Handle(login);
  ASSERT_EQ(signed_in.reply.status, 200u);
  ASSERT_EQ(signed_in.headers.size(), 1u);
  EXPECT_EQ(signed_in.headers[0].first, "Set-Cookie");
  const std::string cookie =
      signed_in.headers[0].second.substr(0, signed_in.headers[0].second.find(';'));

  WebRequest forged = Post("/api/jobs/3/cancel");  // a form on another site: no header
  forged.cookie = cookie;
  EXPECT_EQ(routes.Handle(forged).reply.status, 403u);
  EXPECT_TRUE(acted.empty());

  WebRequest page = forged;
  page.marked = true;
  EXPECT_EQ(routes.Handle(page).reply.status, 200u);
  WebRequest script = Post("/api/jobs/4/resume");
  script.authorization = "Bearer " + kRoutesToken;
  EXPECT_EQ(routes.Handle(script).reply.status, 200u);
  EXPECT_EQ(acted, (std::vector<std::string>{"cancel 3", "resume 4"}));
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
