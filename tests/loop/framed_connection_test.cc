#include "loop/framed_connection.h"

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "loop/frame_splitter.h"
#include "loop/tcp_listener.h"
#include "loop_test_util.h"

namespace radfarm::loop {
namespace {

using testing::Bytes;
using testing::ExpectClosesClean;
using testing::Frame;
using testing::RawClient;
using testing::RunUntil;
using Payload = std::vector<uint8_t>;

// A TCP server on an ephemeral loopback port whose connections record what they get and, by
// default, echo every frame.
class Server {
 public:
  Server(EventLoop& loop, ConnectionOptions options) : options_(options) {
    Result<std::unique_ptr<TcpListener>> listener =
        TcpListener::Listen(loop, {"127.0.0.1", 0},
                            [this](std::unique_ptr<FramedConnection> c) { Accept(std::move(c)); });
    EXPECT_TRUE(listener.ok()) << listener.error();
    if (listener.ok()) listener_ = std::move(listener).value();
  }

  uint16_t port() const { return listener_->port(); }
  const std::string& address() const { return listener_->address(); }

  std::vector<std::unique_ptr<FramedConnection>> connections;
  std::vector<std::vector<Payload>> frames;      // per connection
  std::vector<std::vector<std::string>> closes;  // per connection: every on_close reason
  std::function<void(size_t index)> on_accept;   // runs after Start
  std::function<void(size_t index, const Payload&)> on_frame;  // instead of echoing

  void CloseListener() { listener_.reset(); }

 private:
  void Accept(std::unique_ptr<FramedConnection> connection) {
    const size_t index = connections.size();
    FramedConnection* raw = connection.get();
    connections.push_back(std::move(connection));
    frames.emplace_back();
    closes.emplace_back();
    raw->Start(
        options_,
        [this, index, raw](std::span<const uint8_t> payload) {
          frames[index].emplace_back(payload.begin(), payload.end());
          if (on_frame) {
            on_frame(index, frames[index].back());
          } else {
            EXPECT_TRUE(raw->Send(payload).ok());
          }
        },
        [this, index](const std::string& reason) { closes[index].push_back(reason); });
    if (on_accept) on_accept(index);
  }

  ConnectionOptions options_;
  std::unique_ptr<TcpListener> listener_;
};

std::vector<Payload> SplitFrames(const Payload& bytes) {
  std::vector<Payload> frames;
  FrameSplitter splitter(64u << 20);
  EXPECT_TRUE(splitter
                  .Feed(bytes,
                        [&](std::span<const uint8_t> payload) {
                          frames.emplace_back(payload.begin(), payload.end());
                          return true;
                        })
                  .ok());
  return frames;
}

Payload Pattern(size_t size, uint8_t seed) {
  Payload payload(size);
  for (size_t i = 0; i < size; ++i) payload[i] = static_cast<uint8_t>(seed + i * 7 + i / 251);
  return payload;
}

// Every byte arrives in a read of its own, so a frame boundary falls at every possible offset:
// inside the prefix, between prefix and payload, and inside the payload.
TEST(FramedConnectionTest, EchoesFramesSentOneByteAtATime) {
  EventLoop loop;
  {
    Server server(loop, {});
    RawClient client;
    ASSERT_TRUE(client.ConnectTcp("127.0.0.1", server.port()));
    ASSERT_TRUE(RunUntil(loop, [&] { return server.connections.size() == 1; }));
    FramedConnection& connection = *server.connections[0];

    const std::vector<Payload> sent = {
        Bytes("hello"), {}, Bytes("x"), Pattern(1000, 3), Bytes("end")};
    Payload stream;
    std::vector<size_t> frame_ends;  // offset just past each frame
    for (const Payload& payload : sent) {
      const Payload frame = Frame(payload);
      stream.insert(stream.end(), frame.begin(), frame.end());
      frame_ends.push_back(stream.size());
    }
    size_t complete = 0;
    for (size_t i = 0; i < stream.size(); ++i) {
      ASSERT_TRUE(client.SendAll({stream[i]}));
      ASSERT_TRUE(RunUntil(loop, [&] { return connection.bytes_received() == i + 1; }));
      while (complete < frame_ends.size() && frame_ends[complete] <= i + 1) ++complete;
      ASSERT_EQ(server.frames[0].size(), complete) << "after byte " << i;
    }
    EXPECT_EQ(server.frames[0], sent);

    Payload echoed;
    ASSERT_TRUE(RunUntil(loop, [&] {
      client.ReadAvailable(&echoed);
      return echoed.size() >= stream.size();
    }));
    EXPECT_EQ(SplitFrames(echoed), sent);
    EXPECT_TRUE(server.closes[0].empty());
  }
  ExpectClosesClean(loop);
}

// Every connection of a loop reads into the same buffer (framed_connection.cc): a frame split
// across reads on one connection must survive the other connections' reads in between.
TEST(FramedConnectionTest, PartialFramesOfConnectionsSharingTheReadBufferStayApart) {
  EventLoop loop;
  {
    Server server(loop, {});
    server.on_frame = [](size_t, const Payload&) {};  // record only
    RawClient a, b;
    ASSERT_TRUE(a.ConnectTcp("127.0.0.1", server.port()));
    ASSERT_TRUE(RunUntil(loop, [&] { return server.connections.size() == 1; }));
    ASSERT_TRUE(b.ConnectTcp("127.0.0.1", server.port()));
    ASSERT_TRUE(RunUntil(loop, [&] { return server.connections.size() == 2; }));
    const Payload fa = Frame(Pattern(5000, 1)), fb = Frame(Pattern(3000, 2)),
                  fc = Frame(Pattern(7000, 3));
    const auto sent_to = [&](size_t index, size_t bytes) {
      return RunUntil(loop, [&] { return server.connections[index]->bytes_received() == bytes; });
    };
    ASSERT_TRUE(a.SendAll(Payload(fa.begin(), fa.begin() + 2500)));
    ASSERT_TRUE(sent_to(0, 2500));
    Payload b_first(fb);  // all of B's first frame and half its second
    b_first.insert(b_first.end(), fc.begin(), fc.begin() + 3500);
    ASSERT_TRUE(b.SendAll(b_first));
    ASSERT_TRUE(sent_to(1, b_first.size()));
    ASSERT_TRUE(a.SendAll(Payload(fa.begin() + 2500, fa.end())));
    ASSERT_TRUE(sent_to(0, fa.size()));
    ASSERT_TRUE(b.SendAll(Payload(fc.begin() + 3500, fc.end())));
    ASSERT_TRUE(sent_to(1, fb.size() + fc.size()));
    EXPECT_EQ(server.frames[0], (std::vector<Payload>{Pattern(5000, 1)}));
    EXPECT_EQ(server.frames[1], (std::vector<Payload>{Pattern(3000, 2), Pattern(7000, 3)}));
  }
  ExpectClosesClean(loop);
}

// Two FramedConnections: frames of up to 4 MiB both ways, so writes go partial and queue.
TEST(FramedConnectionTest, EchoesLargeFramesBetweenFramedConnections) {
  EventLoop loop;
  {
    ConnectionOptions options;
    options.max_frame_bytes = 8u << 20;
    Server server(loop, options);
    std::vector<Payload> received;
    std::vector<std::string> client_closes;
    bool connected = false;
    Result<SocketAddress> address = SocketAddress::FromIpLiteral({"127.0.0.1", server.port()});
    ASSERT_TRUE(address.ok());
    Result<std::unique_ptr<FramedConnection>> client = FramedConnection::ConnectTcp(
        loop, *address, options,
        [&](std::span<const uint8_t> p) { received.emplace_back(p.begin(), p.end()); },
        [&](const std::string& reason) { client_closes.push_back(reason); },
        [&] { connected = true; });
    ASSERT_TRUE(client.ok()) << client.error();
    EXPECT_EQ((*client)->peer(), server.address());

    std::vector<Payload> sent;
    for (size_t i = 0; i < 12; ++i) sent.push_back(Pattern(i % 3 == 0 ? (4u << 20) : i * 1000, i));
    for (const Payload& payload : sent)
      ASSERT_TRUE((*client)->Send(payload).ok());  // before connect
    ASSERT_TRUE(RunUntil(loop, [&] { return received.size() == sent.size(); }));
    EXPECT_TRUE(connected);
    EXPECT_EQ(received, sent);
    EXPECT_EQ(server.frames[0], sent);
    EXPECT_EQ((*client)->frames_received(), sent.size());

    (*client)->Close("test over");
    ASSERT_TRUE(
        RunUntil(loop, [&] { return client_closes.size() == 1 && server.closes[0].size() == 1; }));
    EXPECT_EQ(client_closes[0], "test over");
    EXPECT_EQ(server.closes[0][0], "peer closed the connection");
    EXPECT_EQ((*client)->state(), HandleState::kClosed);
  }
  ExpectClosesClean(loop);
}

TEST(FramedConnectionTest, OversizedPrefixClosesOnlyThatConnection) {
  EventLoop loop;
  {
    ConnectionOptions options;
    options.max_frame_bytes = 1024;
    Server server(loop, options);
    RawClient bad;
    RawClient good;
    ASSERT_TRUE(bad.ConnectTcp("127.0.0.1", server.port()));
    ASSERT_TRUE(RunUntil(loop, [&] { return server.connections.size() == 1; }));
    ASSERT_TRUE(good.ConnectTcp("127.0.0.1", server.port()));
    ASSERT_TRUE(RunUntil(loop, [&] { return server.connections.size() == 2; }));

    Payload prefix(4);
    WriteFramePrefix(1025, prefix.data());
    ASSERT_TRUE(bad.SendAll(prefix));
    ASSERT_TRUE(RunUntil(loop, [&] { return !server.closes[0].empty(); }));
    EXPECT_EQ(server.closes[0],
              std::vector<std::string>{"frame of 1025 bytes exceeds the limit of 1024 bytes"});
    Payload ignored;
    ASSERT_TRUE(RunUntil(loop, [&] { return !bad.ReadAvailable(&ignored); }));  // we hung up

    ASSERT_TRUE(good.SendAll(Frame(Pattern(1024, 9))));
    Payload echoed;
    ASSERT_TRUE(RunUntil(loop, [&] {
      good.ReadAvailable(&echoed);
      return echoed.size() == 4 + 1024;
    }));
    EXPECT_EQ(SplitFrames(echoed), std::vector<Payload>{Pattern(1024, 9)});
    EXPECT_TRUE(server.closes[1].empty());
    EXPECT_EQ(server.closes[0].size(), 1u);  // exactly once
  }
  ExpectClosesClean(loop);
}

// Hostile neighbours: a peer holding the whole frame budget in an unfinished frame made every
// other peer's next buffered frame fail. Now that peer is the one closed, with the reason.
TEST(FramedConnectionTest, FrameBudgetClosesTheLargestHolderAndTheSmallFrameGetsThrough) {
  EventLoop loop;
  {
    constexpr uint32_t kBudget = 1u << 20;
    ConnectionOptions options;
    options.max_frame_bytes = 4u << 20;
    options.frame_budget = std::make_shared<FrameBudget>(kBudget, "the budget");
    Server server(loop, options);
    RawClient hog;
    RawClient honest;
    ASSERT_TRUE(hog.ConnectTcp("127.0.0.1", server.port()));
    ASSERT_TRUE(RunUntil(loop, [&] { return server.connections.size() == 1; }));
    ASSERT_TRUE(honest.ConnectTcp("127.0.0.1", server.port()));
    ASSERT_TRUE(RunUntil(loop, [&] { return server.connections.size() == 2; }));

    // A frame of exactly the budget, all but its last byte: its buffer holds the whole budget.
    Payload hog_bytes = Frame(Pattern(kBudget, 7));
    hog_bytes.pop_back();
    ASSERT_TRUE(hog.SendAll(hog_bytes));
    ASSERT_TRUE(RunUntil(loop, [&] { return options.frame_budget->held() == kBudget; }));

    const Payload small = Pattern(300u << 10, 8);  // more than one read: buffered
    ASSERT_TRUE(honest.SendAll(Frame(small)));
    Payload echoed;
    ASSERT_TRUE(RunUntil(loop, [&] {
      honest.ReadAvailable(&echoed);
      return echoed.size() == 4 + small.size();
    }));
    EXPECT_EQ(SplitFrames(echoed), std::vector<Payload>{small});
    EXPECT_TRUE(server.closes[1].empty());
    ASSERT_TRUE(RunUntil(loop, [&] { return !server.closes[0].empty(); }));
    EXPECT_NE(server.closes[0][0].find("closed holding the most bytes of unfinished frames"),
              std::string::npos)
        << server.closes[0][0];
    EXPECT_EQ(options.frame_budget->evicted(), 1u);
    EXPECT_EQ(options.frame_budget->held(), 0u);
  }
  ExpectClosesClean(loop);
}

// A peer that never reads cannot make us buffer without bound.
TEST(FramedConnectionTest, PeerThatDoesNotReadHitsTheSendQueueLimit) {
  EventLoop loop;
  {
    ConnectionOptions options;
    options.max_queued_bytes = 1u << 20;
    Server server(loop, options);
    RawClient lazy;
    ASSERT_TRUE(lazy.ConnectTcp("127.0.0.1", server.port()));
    lazy.SetReceiveBuffer(4096);
    ASSERT_TRUE(RunUntil(loop, [&] { return server.connections.size() == 1; }));
    FramedConnection& connection = *server.connections[0];

    const Payload chunk = Pattern(64 * 1024, 1);
    std::string error;
    size_t sent = 0;
    // The kernel's socket buffers take a few MiB first; after that, libuv queues.
    while (sent < (256u << 20)) {
      Status status = connection.Send(chunk);
      if (!status.ok()) {
        error = status.error();
        break;
      }
      sent += chunk.size();
      EXPECT_LE(connection.queued_bytes(), options.max_queued_bytes + chunk.size() + 4);
    }
    EXPECT_NE(error.find("send queue full"), std::string::npos) << error;
    EXPECT_FALSE(connection.Send(chunk).ok());
    ASSERT_TRUE(RunUntil(loop, [&] { return !server.closes[0].empty(); }));
    EXPECT_EQ(server.closes[0], std::vector<std::string>{error});
  }
  ExpectClosesClean(loop);
}

TEST(FramedConnectionTest, ReadIdleTimeoutClosesASilentPeer) {
  EventLoop loop;
  {
    ConnectionOptions options;
    options.read_idle_timeout = std::chrono::milliseconds(100);
    Server server(loop, options);
    uint64_t started = 0;
    server.on_accept = [&](size_t) { started = loop.NowMs(); };
    RawClient silent;
    ASSERT_TRUE(silent.ConnectTcp("127.0.0.1", server.port()));
    ASSERT_TRUE(
        RunUntil(loop, [&] { return server.closes.size() == 1 && !server.closes[0].empty(); }));
    EXPECT_GE(loop.NowMs() - started, 100u);
    EXPECT_EQ(server.closes[0], std::vector<std::string>{"no data for 100 ms (read idle timeout)"});
  }
  ExpectClosesClean(loop);
}

// Any received byte restarts the idle clock: a peer that trickles bytes for longer than the
// timeout stays; once it stops, it is closed. Gaps are a tenth of the timeout, so a loaded machine
// has ample slack.
TEST(FramedConnectionTest, ReceivedBytesRestartTheIdleTimeout) {
  EventLoop loop;
  {
    ConnectionOptions options;
    options.read_idle_timeout = std::chrono::milliseconds(1000);
    Server server(loop, options);
    RawClient client;
    ASSERT_TRUE(client.ConnectTcp("127.0.0.1", server.port()));
    ASSERT_TRUE(RunUntil(loop, [&] { return server.connections.size() == 1; }));
    const uint64_t start = loop.NowMs();
    uint64_t last_send = start;
    ASSERT_TRUE(RunUntil(loop, [&] {
      if (loop.NowMs() - last_send >= 100) {
        EXPECT_TRUE(client.SendAll({0}));  // a byte of a frame that never completes
        last_send = loop.NowMs();
      }
      return loop.NowMs() - start >= 2500 || !server.closes[0].empty();
    }));
    EXPECT_TRUE(server.closes[0].empty()) << server.closes[0][0];
    ASSERT_TRUE(RunUntil(loop, [&] { return !server.closes[0].empty(); }));
    EXPECT_EQ(server.closes[0],
              std::vector<std::string>{"no data for 1000 ms (read idle timeout)"});
  }
  ExpectClosesClean(loop);
}

TEST(FramedConnectionTest, RefusedConnectReachesOnClose) {
  EventLoop loop;
  {
    uint16_t port;
    {
      Server gone(loop, {});
      port = gone.port();
    }
    Result<SocketAddress> address = SocketAddress::FromIpLiteral({"127.0.0.1", port});
    ASSERT_TRUE(address.ok());
    std::vector<std::string> closes;
    bool connected = false;
    Result<std::unique_ptr<FramedConnection>> client = FramedConnection::ConnectTcp(
        loop, *address, {}, [](auto) {}, [&](const std::string& r) { closes.push_back(r); },
        [&] { connected = true; });
    ASSERT_TRUE(client.ok()) << client.error();
    ASSERT_TRUE((*client)->Send(Bytes("never sent")).ok());  // queued; freed when connect fails
    ASSERT_TRUE(RunUntil(loop, [&] { return !closes.empty(); }));
    EXPECT_FALSE(connected);
    EXPECT_EQ(closes.size(), 1u);
    EXPECT_NE(closes[0].find("ECONNREFUSED"), std::string::npos) << closes[0];
    EXPECT_NE(closes[0].find(address->ToString()), std::string::npos) << closes[0];
  }
  ExpectClosesClean(loop);
}

// The master's "send an error, then hang up": the last frame must reach the peer.
TEST(FramedConnectionTest, CloseAfterFlushDeliversTheLastFrames) {
  EventLoop loop;
  {
    Server server(loop, {});
    server.on_accept = [&](size_t index) {
      FramedConnection& c = *server.connections[index];
      ASSERT_TRUE(c.Send(Pattern(3u << 20, 5)).ok());
      ASSERT_TRUE(c.Send(Bytes("bye")).ok());
      c.CloseAfterFlush("handshake refused");
      EXPECT_EQ(c.state(), HandleState::kClosing);
      EXPECT_FALSE(c.Send(Bytes("late")).ok());
    };
    Result<SocketAddress> address = SocketAddress::FromIpLiteral({"127.0.0.1", server.port()});
    std::vector<Payload> received;
    std::vector<std::string> client_closes;
    Result<std::unique_ptr<FramedConnection>> client = FramedConnection::ConnectTcp(
        loop, *address, {}, [&](auto p) { received.emplace_back(p.begin(), p.end()); },
        [&](const std::string& r) { client_closes.push_back(r); });
    ASSERT_TRUE(client.ok()) << client.error();
    ASSERT_TRUE(RunUntil(loop, [&] {
      return client_closes.size() == 1 && server.closes.size() == 1 && !server.closes[0].empty();
    }));
    EXPECT_EQ(received, (std::vector<Payload>{Pattern(3u << 20, 5), Bytes("bye")}));
    EXPECT_EQ(client_closes[0], "peer closed the connection");
    EXPECT_EQ(server.closes[0], std::vector<std::string>{"handshake refused"});
  }
  ExpectClosesClean(loop);
}

TEST(FramedConnectionTest, CallbacksMayDestroyTheirConnection) {
  EventLoop loop;
  {
    Server server(loop, {});
    server.on_frame = [&](size_t index, const Payload&) {
      server.connections[index].reset();  // e.g. a protocol error: drop it on the spot
    };
    RawClient client;
    ASSERT_TRUE(client.ConnectTcp("127.0.0.1", server.port()));
    Payload two = Frame(Bytes("one"));
    const Payload second = Frame(Bytes("two"));
    two.insert(two.end(), second.begin(), second.end());
    ASSERT_TRUE(client.SendAll(two));  // likely one read: the second frame must not be delivered
    Payload ignored;
    ASSERT_TRUE(RunUntil(loop, [&] { return !client.ReadAvailable(&ignored); }));
    EXPECT_EQ(server.frames[0].size(), 1u);
    EXPECT_TRUE(server.closes[0].empty());  // destroying closes silently
  }
  ExpectClosesClean(loop);
}

TEST(FramedConnectionTest, OnCloseMayDestroyTheConnection) {
  EventLoop loop;
  {
    ConnectionOptions options;
    options.read_idle_timeout = std::chrono::milliseconds(1);
    Server server(loop, options);
    std::unique_ptr<FramedConnection> client;
    Result<SocketAddress> address = SocketAddress::FromIpLiteral({"127.0.0.1", server.port()});
    int closes = 0;
    Result<std::unique_ptr<FramedConnection>> made = FramedConnection::ConnectTcp(
        loop, *address, {}, [](auto) {},
        [&](const std::string&) {
          ++closes;
          client.reset();
        });
    ASSERT_TRUE(made.ok());
    client = std::move(made).value();
    ASSERT_TRUE(RunUntil(loop, [&] { return client == nullptr; }));
    EXPECT_EQ(closes, 1);
  }
  ExpectClosesClean(loop);
}

TEST(FramedConnectionTest, SendChecksTheFrameLimitAndPrefix) {
  EventLoop loop;
  {
    ConnectionOptions options;
    options.max_frame_bytes = 16;
    Server server(loop, options);
    Result<SocketAddress> address = SocketAddress::FromIpLiteral({"127.0.0.1", server.port()});
    std::vector<Payload> received;
    Result<std::unique_ptr<FramedConnection>> client = FramedConnection::ConnectTcp(
        loop, *address, options, [&](auto p) { received.emplace_back(p.begin(), p.end()); },
        [](const std::string&) {});
    ASSERT_TRUE(client.ok());
    FramedConnection& c = **client;
    Status too_big = c.Send(Pattern(17, 0));
    ASSERT_FALSE(too_big.ok());
    EXPECT_EQ(too_big.error(), "frame of 17 bytes exceeds the limit of 16 bytes");
    EXPECT_EQ(c.state(), HandleState::kOpen);  // our own mistake does not cost the connection

    Payload wrong = Frame(Bytes("abc"));
    wrong[0] = 4;
    EXPECT_FALSE(c.SendPrefixed(std::move(wrong)).ok());
    ASSERT_TRUE(c.SendPrefixed(Frame(Bytes("prefixed"))).ok());
    ASSERT_TRUE(RunUntil(loop, [&] { return received.size() == 1; }));
    EXPECT_EQ(received[0], Bytes("prefixed"));
  }
  ExpectClosesClean(loop);
}

}  // namespace
}  // namespace radfarm::loop
