#include "daemon/console/web/http_server.h"

#include <gtest/gtest.h>

#include <mutex>
#include <string>
#include <vector>

#include "loop/log.h"
#include "testing/http_client.h"

namespace radfarm::web {
namespace {

// Malformed requests made libmicrohttpd log two warnings each, with no limit: one client filled
// the log with thousands of lines a second.
TEST(HttpServerTest, MalformedRequestsLogNoMoreLinesThanTheLimit) {
  std::mutex mutex;
  std::vector<std::string> lines;
  loop::SetLogSink([&](std::string_view line) {
    std::lock_guard lock(mutex);
    lines.emplace_back(line);
  });
  StatusBoard board;
  auto routes = std::make_unique<WebRoutes>(WebAccess(true, ""), board, WebHandlers{});
  // A window far longer than the test, so the count does not depend on how fast it runs.
  auto server =
      HttpServer::Start({"127.0.0.1", 0}, std::move(routes), board, std::chrono::hours(1));
  ASSERT_TRUE(server.ok()) << server.error();
  constexpr int kRequests = 100;
  for (int i = 0; i < kRequests; ++i) {
    // A header line without a colon; the answer (or a closed connection) does not matter here.
    (void)testing::HttpRequest((*server)->address(), "GET", "/", {"no colon in this line"});
  }
  (*server)->Stop();  // joins the HTTP threads: every line they would log is in
  loop::SetLogSink({});
  size_t warnings = 0;
  for (const std::string& line : lines) {
    if (line.find("WARN") != std::string::npos && line.find("http:") != std::string::npos) {
      ++warnings;
    }
  }
  EXPECT_GE(warnings, 1u);
  EXPECT_LE(warnings, HttpServer::kLogLines);
  EXPECT_LT(lines.size(), size_t{kRequests});
}

}  // namespace
}  // namespace radfarm::web
