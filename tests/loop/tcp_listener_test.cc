#include "loop/tcp_listener.h"

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <unistd.h>

#include <memory>
#include <string>
#include <vector>

#include "loop/host_port.h"
#include "loop/listen_block.h"
#include "loop/log.h"
#include "loop_test_util.h"

namespace radfarm::loop {
namespace {

using testing::Bytes;
using testing::ExpectClosesClean;
using testing::RawClient;
using testing::RunUntil;

// Listens on `listen` (port 0), then connects to the reported address with a FramedConnection
// and checks one frame gets across. Returns the reported address.
std::string ListenAndConnect(EventLoop& loop, const std::string& listen) {
  Result<HostPort> host_port = ParseHostPort(listen, "--listen");
  EXPECT_TRUE(host_port.ok()) << host_port.error();
  std::vector<std::unique_ptr<FramedConnection>> accepted;
  std::vector<std::vector<uint8_t>> frames;
  Result<std::unique_ptr<TcpListener>> listener =
      TcpListener::Listen(loop, *host_port, [&](std::unique_ptr<FramedConnection> c) {
        c->Start(
            {}, [&](auto p) { frames.emplace_back(p.begin(), p.end()); }, [](auto&) {});
        accepted.push_back(std::move(c));
      });
  if (!listener.ok()) {
    ADD_FAILURE() << listener.error();
    return "";
  }
  const std::string reported = (*listener)->address();

  // What the master writes to STATE/listen.addr must parse back and be connectable.
  Result<HostPort> parsed = ParseHostPort(reported, "listen.addr");
  EXPECT_TRUE(parsed.ok()) << parsed.error();
  EXPECT_NE(parsed->port, 0);
  EXPECT_EQ(parsed->port, (*listener)->port());
  Result<SocketAddress> address = SocketAddress::FromIpLiteral(*parsed);
  EXPECT_TRUE(address.ok()) << address.error();
  Result<std::unique_ptr<FramedConnection>> client = FramedConnection::ConnectTcp(
      loop, *address, {}, [](auto) {}, [](auto&) {});
  EXPECT_TRUE(client.ok()) << client.error();
  EXPECT_TRUE((*client)->Send(Bytes("ping")).ok());
  EXPECT_TRUE(RunUntil(loop, [&] { return frames.size() == 1; }));
  EXPECT_EQ(frames.at(0), Bytes("ping"));
  EXPECT_EQ(accepted.at(0)->peer().rfind(parsed->host == "::1" ? "[::1]:" : "127.0.0.1:", 0), 0u)
      << accepted[0]->peer();
  return reported;
}

TEST(TcpListenerTest, EphemeralIpv4PortIsReportedAndConnectable) {
  EventLoop loop;
  const std::string reported = ListenAndConnect(loop, "127.0.0.1:0");
  EXPECT_EQ(reported.rfind("127.0.0.1:", 0), 0u) << reported;
  ExpectClosesClean(loop);
}

TEST(TcpListenerTest, EphemeralIpv6PortIsReportedAndConnectable) {
  {
    EventLoop probe;  // some containers have no IPv6 loopback
    Result<std::unique_ptr<TcpListener>> listener =
        TcpListener::Listen(probe, {"::1", 0}, [](auto) {});
    if (!listener.ok()) {
      listener = Error{""};
      ExpectClosesClean(probe);
      GTEST_SKIP() << "no IPv6 loopback here";
    }
  }
  EventLoop loop;
  const std::string reported = ListenAndConnect(loop, "[::1]:0");
  EXPECT_EQ(reported.rfind("[::1]:", 0), 0u) << reported;
  ExpectClosesClean(loop);
}

TEST(TcpListenerTest, APortInUseIsAnErrorNamingTheAddress) {
  EventLoop loop;
  {
    Result<std::unique_ptr<TcpListener>> first =
        TcpListener::Listen(loop, {"127.0.0.1", 0}, [](auto) {});
    ASSERT_TRUE(first.ok()) << first.error();
    Result<std::unique_ptr<TcpListener>> second =
        TcpListener::Listen(loop, {"127.0.0.1", (*first)->port()}, [](auto) {});
    ASSERT_FALSE(second.ok());
    EXPECT_NE(second.error().find("listen on " + (*first)->address()), std::string::npos)
        << second.error();
    EXPECT_NE(second.error().find("EADDRINUSE"), std::string::npos) << second.error();
    EXPECT_EQ((*first)->state(), HandleState::kOpen);
  }
  ExpectClosesClean(loop);
}

TEST(TcpListenerTest, CloseStopsAccepting) {
  EventLoop loop;
  Result<std::unique_ptr<TcpListener>> listener =
      TcpListener::Listen(loop, {"127.0.0.1", 0}, [](auto) {});
  ASSERT_TRUE(listener.ok()) << listener.error();
  (*listener)->Close();
  EXPECT_EQ((*listener)->state(), HandleState::kClosing);
  ASSERT_TRUE(RunUntil(loop, [&] { return (*listener)->state() == HandleState::kClosed; }));
  ExpectClosesClean(loop);  // the wrapper may outlive the handle
}

size_t CountContaining(const std::vector<std::string>& lines, const std::string& text) {
  size_t n = 0;
  for (const std::string& line : lines) n += line.find(text) != std::string::npos ? 1 : 0;
  return n;
}

// Hostile neighbours: with the descriptors used up, a failing `accept` left no log line (libuv
// accepts and drops such connections itself). Now the last descriptors are kept: a connection
// past them is refused, and that is logged, at most kAcceptLogLines lines per window.
TEST(TcpListenerTest, AConnectionPastTheDescriptorLimitIsRefusedAndLogged) {
  std::vector<std::string> lines;
  SetLogSink([&](std::string_view line) { lines.emplace_back(line); });
  struct SinkReset {
    ~SinkReset() { SetLogSink(nullptr); }
  } sink_reset;  // before `lines` goes, even when an assertion returns early
  rlimit saved{};
  ASSERT_EQ(getrlimit(RLIMIT_NOFILE, &saved), 0);
  const std::string kRefused = "out of file descriptors";
  {
    EventLoop loop;
    std::vector<std::unique_ptr<FramedConnection>> accepted;
    Result<std::unique_ptr<TcpListener>> listener =
        TcpListener::Listen(loop, {"127.0.0.1", 0}, [&](std::unique_ptr<FramedConnection> c) {
          c->Start(
              {}, [](auto) {}, [](auto&) {});
          accepted.push_back(std::move(c));
        });
    ASSERT_TRUE(listener.ok()) << listener.error();
    // Room for 40 more descriptors: each connection takes two, its client's and the accepted one.
    const int lowest_free = dup(0);
    ASSERT_GE(lowest_free, 0);
    close(lowest_free);
    rlimit low = saved;
    low.rlim_cur = static_cast<rlim_t>(lowest_free) + 40;
    ASSERT_EQ(setrlimit(RLIMIT_NOFILE, &low), 0);
    std::vector<std::unique_ptr<RawClient>> clients;
    while (CountContaining(lines, kRefused) == 0 && clients.size() < 20) {
      clients.push_back(std::make_unique<RawClient>());
      ASSERT_TRUE(clients.back()->ConnectTcp("127.0.0.1", (*listener)->port())) << clients.size();
      ASSERT_TRUE(RunUntil(loop,
                           [&] {
                             return accepted.size() == clients.size() ||
                                    CountContaining(lines, kRefused) > 0;
                           }))
          << clients.size() << " clients, " << accepted.size() << " accepted";
    }
    ASSERT_EQ(CountContaining(lines, kRefused), 1u);
    EXPECT_NE(CountContaining(lines, "RLIMIT_NOFILE"), 0u);
    EXPECT_EQ(accepted.size(), clients.size() - 1);
    std::vector<uint8_t> ignored;
    EXPECT_TRUE(RunUntil(loop, [&] { return !clients.back()->ReadAvailable(&ignored); }));

    // A flood of them logs a few lines, not one each.
    for (int i = 0; i < 12; ++i) {
      clients.push_back(std::make_unique<RawClient>());
      ASSERT_TRUE(clients.back()->ConnectTcp("127.0.0.1", (*listener)->port()));
      ASSERT_TRUE(RunUntil(loop, [&] { return !clients.back()->ReadAvailable(&ignored); }));
    }
    EXPECT_EQ(CountContaining(lines, kRefused), internal::kAcceptLogLines);
    ASSERT_EQ(setrlimit(RLIMIT_NOFILE, &saved), 0);
    clients.clear();
    accepted.clear();
    listener->reset();
    ExpectClosesClean(loop);
  }
}

}  // namespace
}  // namespace radfarm::loop
