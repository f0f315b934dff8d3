// FramedConnection: one TCP or Unix stream carrying length-prefixed frames (frame_splitter.h).
// TcpListener/UnixListener hand out accepted ones; ConnectTcp/ConnectUnix make client ones.
//
// Threads: loop thread only; every callback runs there. Ownership: the caller owns the
// FramedConnection; the socket, buffers and callbacks live in a block freed in libuv's close
// callback (handle_block.h), so a callback may destroy the connection.
//
// Lifecycle:
//   open     --Close(reason), a read/write error, EOF, an oversized frame, a full send queue,
//             the read-idle timeout, evicted from the frame budget-->                  closing
//   open     --CloseAfterFlush(reason): stop reading, send what is queued, then-->     closing
//   closing  --libuv closed the socket: on_close(reason)-->                            closed
// on_close runs exactly once per connection, with the first reason, after the socket is closed;
// it may destroy the connection. Destroying a connection closes it silently (no on_close).
//
// Limits: a peer announcing a frame above max_frame_bytes is dropped before anything is allocated
// for it; when a partial frame would pass the frame_budget, the connection holding the most of it
// is dropped (frame_budget.h), this one or another; if more than max_queued_bytes wait to be
// written (the peer does not read), the connection is closed rather than buffering without bound.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "base/result.h"
#include "loop/event_loop.h"
#include "loop/frame_budget.h"
#include "loop/handle_block.h"
#include "loop/socket_address.h"

namespace radfarm::loop {

namespace internal {
struct ListenBlock;
}

// on_close's reason when the peer ended the stream (EOF) while the connection was open.
inline constexpr const char* kPeerClosedReason = "peer closed the connection";

struct ConnectionOptions {
  uint32_t max_frame_bytes = 16u << 20;  // payload limit, both directions
  size_t max_queued_bytes = 64u << 20;   // unwritten bytes before a slow peer is dropped
  // Close a peer that sends no byte for this long (0: never). Counts from Start() (connecting
  // included); any received byte restarts it. Change it with SetReadIdleTimeout.
  std::chrono::milliseconds read_idle_timeout{0};
  std::chrono::milliseconds flush_timeout{5000};  // CloseAfterFlush's deadline
  // Shared by connections whose unfinished frames together may hold only so much (none: each
  // holds at most its own frame limit).
  std::shared_ptr<FrameBudget> frame_budget;
};

class FramedConnection {
 public:
  // The payload without its prefix; valid during the call only.
  using OnFrame = std::function<void(std::span<const uint8_t> payload)>;
  using OnClose = std::function<void(const std::string& reason)>;

  // Client side. Returns at once; on_connected runs once the connection is up (frames may be
  // sent before: they are queued). A failed connect reaches on_close. Connecting counts against
  // the read-idle timeout.
  static Result<std::unique_ptr<FramedConnection>> ConnectTcp(
      EventLoop& loop, const SocketAddress& address, const ConnectionOptions& options,
      OnFrame on_frame, OnClose on_close, std::function<void()> on_connected = {});
  static Result<std::unique_ptr<FramedConnection>> ConnectUnix(
      EventLoop& loop, const std::string& path, const ConnectionOptions& options, OnFrame on_frame,
      OnClose on_close, std::function<void()> on_connected = {});

  ~FramedConnection() = default;
  FramedConnection(const FramedConnection&) = delete;
  FramedConnection& operator=(const FramedConnection&) = delete;

  // For accepted connections: starts reading. Once. Until then nothing is read (Send works).
  void Start(const ConnectionOptions& options, OnFrame on_frame, OnClose on_close);

  // Queues one frame: the prefix, then `payload`. Errors: the connection is not open (closed or
  // flushing), the payload is over max_frame_bytes (the connection stays open), or the send queue
  // would pass max_queued_bytes (the connection is closed with that reason).
  Status Send(std::span<const uint8_t> payload);
  Status Send(std::vector<uint8_t>&& payload);  // no copy
  // A frame whose first 4 bytes already hold its payload length (protocol::EncodeFrame's output).
  Status SendPrefixed(std::vector<uint8_t>&& frame);

  void Close(const std::string& reason);  // no-op unless open
  void CloseAfterFlush(const std::string& reason);
  void SetReadIdleTimeout(std::chrono::milliseconds timeout);
  // The limit of the frames received from now on (after Start; the send limit stays
  // options.max_frame_bytes). A server lowers it for peers it does not trust yet (a handshake
  // frame is a few hundred bytes) and raises it once they authenticate or announce what comes.
  void SetMaxReceiveFrameBytes(uint32_t max_frame_bytes);

  // "127.0.0.1:53412", "[::1]:7000", "unix:/run/radfarm/control.sock (pid 12 uid 0)". For logs.
  const std::string& peer() const { return peer_; }
  // kClosing from CloseAfterFlush on.
  HandleState state() const;
  size_t queued_bytes() const;  // accepted by Send, not yet handed to the kernel
  uint64_t bytes_received() const;
  uint64_t frames_received() const;

 private:
  friend struct internal::ListenBlock;
  struct Impl;
  FramedConnection() = default;
  // Accepts a pending connection on `server` (a listener's handle).
  static Result<std::unique_ptr<FramedConnection>> Accept(uv_stream_t* server, bool unix_socket,
                                                          const std::string& listener_name);
  Status Write(std::vector<uint8_t>&& bytes, bool has_prefix);

  internal::BlockRef<Impl> block_;
  std::string peer_;
};

}  // namespace radfarm::loop
