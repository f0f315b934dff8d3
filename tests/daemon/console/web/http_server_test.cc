#include "daemon/console/web/http_server.h"

#include <gtest/gtest.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>

#include <chrono>
#include <mutex>
#include <string>
#include <vector>

#include "base/unique_fd.h"
#include "loop/host_port.h"
#include "loop/log.h"
#include "loop/socket_address.h"
#include "testing/http_client.h"

namespace radfarm::web {
namespace {

using Clock = std::chrono::steady_clock;

// A client socket connected to `address`, or an invalid one.
UniqueFd Connect(const std::string& address) {
  Result<loop::HostPort> hp = loop::ParseHostPort(address, "address");
  if (!hp) return UniqueFd();
  Result<loop::SocketAddress> sa = loop::SocketAddress::FromIpLiteral(*hp);
  if (!sa) return UniqueFd();
  UniqueFd fd(::socket(sa->family(), SOCK_STREAM | SOCK_CLOEXEC, 0));
  if (!fd.valid() || ::connect(fd.get(), sa->get(), sizeof(sockaddr_in)) != 0) return UniqueFd();
  return fd;
}

bool Send(int fd, const std::string& text) {
  return ::send(fd, text.data(), text.size(), MSG_NOSIGNAL) == static_cast<ssize_t>(text.size());
}

// Reads from `fd` until `marker` has arrived (true), the server closes (true if `marker` is
// empty) or `timeout` passes.
bool ReadUntil(int fd, const std::string& marker, std::chrono::milliseconds timeout,
               std::string* out) {
  const auto deadline = Clock::now() + timeout;
  char buffer[4096];
  while (Clock::now() < deadline) {
    if (!marker.empty() && out->find(marker) != std::string::npos) return true;
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, 100) <= 0) continue;
    const ssize_t n = ::recv(fd, buffer, sizeof buffer, 0);
    if (n <= 0) return marker.empty() || out->find(marker) != std::string::npos;
    out->append(buffer, static_cast<size_t>(n));
  }
  return false;
}

std::string EventsRequest(const std::string& address) {
  return "GET /api/events HTTP/1.1\r\nHost: " + address + "\r\n\r\n";
}

std::unique_ptr<HttpServer> StartServer(StatusBoard& board, HttpServer::Limits limits = {}) {
  auto routes = std::make_unique<WebRoutes>(WebAccess(true, ""), board, WebHandlers{});
  auto server = HttpServer::Start({"127.0.0.1", 0}, std::move(routes), board, limits);
  EXPECT_TRUE(server.ok()) << server.error();
  return server.ok() ? std::move(*server) : nullptr;
}

StatusSnapshot Snapshot() {
  StatusSnapshot snapshot;
  snapshot.status_json = R"({"jobs":[]})";
  return snapshot;
}

// A client sending its request a byte at a time held the connection for ever: libmicrohttpd's
// idle timeout restarts on every byte. The request deadline does not.
TEST(HttpServerTest, ATrickleCannotHoldAConnectionPastTheRequestDeadline) {
  StatusBoard board;
  HttpServer::Limits limits;
  limits.request_deadline = std::chrono::milliseconds(500);
  auto server = StartServer(board, limits);
  ASSERT_TRUE(server);
  UniqueFd fd = Connect(server->address());
  ASSERT_TRUE(fd.valid());
  const std::string request = "GET / HTTP/1.1\r\nX-Slow: " + std::string(1000, 'a');
  bool closed = false;
  // A byte every 100 ms for at most 30 s: far longer than the deadline, far shorter than a test
  // timeout.
  for (size_t i = 0; i < request.size() && !closed; ++i) {
    if (!Send(fd.get(), request.substr(i, 1))) {
      closed = true;
      break;
    }
    pollfd p{fd.get(), POLLIN, 0};
    if (::poll(&p, 1, 100) > 0) {
      char c;
      closed = ::recv(fd.get(), &c, 1, 0) <= 0;
    }
    if (i >= 300) break;
  }
  EXPECT_TRUE(closed);
  board.Close();
}

// Every open tab held a stream (and a connection and a thread) for as long as it stayed open.
TEST(HttpServerTest, TheNewestEventStreamEvictsTheOldest) {
  StatusBoard board;
  board.Publish(Snapshot());
  HttpServer::Limits limits;
  limits.max_event_streams = 2;
  auto server = StartServer(board, limits);
  ASSERT_TRUE(server);
  std::vector<UniqueFd> streams;
  std::vector<std::string> read(3);
  for (size_t i = 0; i < 3; ++i) {
    streams.push_back(Connect(server->address()));
    ASSERT_TRUE(streams[i].valid());
    ASSERT_TRUE(Send(streams[i].get(), EventsRequest(server->address())));
    ASSERT_TRUE(ReadUntil(streams[i].get(), "event: status", std::chrono::seconds(30), &read[i]));
  }
  EXPECT_TRUE(ReadUntil(streams[0].get(), "event: evicted", std::chrono::seconds(30), &read[0]))
      << read[0];
  // The second is still live: a new snapshot reaches it, and it was not evicted.
  board.Publish(Snapshot());
  std::string more;
  EXPECT_TRUE(ReadUntil(streams[1].get(), "event: status", std::chrono::seconds(30), &more));
  EXPECT_EQ(read[1].find("evicted"), std::string::npos);
  EXPECT_EQ(more.find("evicted"), std::string::npos);
  board.Close();
}

// 64 slow clients or 64 open tabs, all from one address, made the page time out (and 16 of
// them refused everyone else on that address). Now the page answers while they are all open.
TEST(HttpServerTest, ThePageAnswersWhile64TricklesAnd64StreamsAreOpen) {
  StatusBoard board;
  board.Publish(Snapshot());
  auto server = StartServer(board);
  ASSERT_TRUE(server);
  std::vector<UniqueFd> clients;
  for (int i = 0; i < 64; ++i) {
    clients.push_back(Connect(server->address()));
    if (clients.back().valid()) Send(clients.back().get(), "GET / HTTP/1.1\r\nX-Slow: a");
  }
  for (int i = 0; i < 64; ++i) {
    clients.push_back(Connect(server->address()));
    if (clients.back().valid()) Send(clients.back().get(), EventsRequest(server->address()));
  }
  // Generous: what matters is that it answers while they are open, not how fast.
  Result<testing::HttpResponse> page = testing::HttpRequest(server->address(), "GET", "/api/status",
                                                            {}, "", std::chrono::seconds(30));
  ASSERT_TRUE(page.ok()) << page.error();
  EXPECT_EQ(page->status, 200);
  Result<testing::HttpResponse> metrics =
      testing::HttpRequest(server->address(), "GET", "/metrics", {}, "", std::chrono::seconds(30));
  ASSERT_TRUE(metrics.ok()) << metrics.error();
  board.Close();
}

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
  HttpServer::Limits limits;
  limits.log_window = std::chrono::hours(1);
  auto server = HttpServer::Start({"127.0.0.1", 0}, std::move(routes), board, limits);
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
