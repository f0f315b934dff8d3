#include "loop/framed_connection.h"

#include <sys/resource.h>
#include <sys/socket.h>
#include <sys/un.h>

#include <array>
#include <string>

#include "loop/check.h"
#include "loop/frame_splitter.h"
#include "loop/uv_error.h"

namespace radfarm::loop {
namespace {

constexpr size_t kReadBufferBytes = 64 * 1024;
// Descriptors kept for the process's own files (the store, scenes, logs) when accepting.
constexpr uint64_t kSpareDescriptors = 32;

// Descriptors are handed out lowest first, so a new socket's number is about how many are open.
// Past the spare ones a connection is refused with this error: at the limit itself the kernel's
// EMFILE has libuv accept and drop connections without a word (its reserve descriptor trick).
Status CheckDescriptorRoom(int fd) {
  rlimit limit{};
  if (fd < 0 || getrlimit(RLIMIT_NOFILE, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY) {
    return Ok{};
  }
  if (uint64_t(fd) + kSpareDescriptors < limit.rlim_cur) return Ok{};
  return Error{"refused: out of file descriptors (this one is number " + std::to_string(fd) +
               " of the " + std::to_string(limit.rlim_cur) + " allowed, RLIMIT_NOFILE; the last " +
               std::to_string(kSpareDescriptors) + " are kept for the process's own files)"};
}

// The buffer every connection of this thread's loop reads into. OnRead consumes it before it
// returns (FrameSplitter copies a partial frame), and libuv reads one stream at a time, so one
// buffer serves all: a buffer a connection, zeroed and paged in at its first read, costs a master
// with many agents memory and CPU in proportion to them.
char* ThreadReadBuffer() {
  thread_local const std::unique_ptr<char[]> buffer(new char[kReadBufferBytes]);
  return buffer.get();
}

std::string Millis(std::chrono::milliseconds ms) { return std::to_string(ms.count()) + " ms"; }

// One Send: the buffers must live until libuv's write callback.
struct WriteRequest {
  uv_write_t req;
  std::array<uint8_t, kFramePrefixBytes> prefix;
  std::vector<uint8_t> bytes;
};

}  // namespace

struct FramedConnection::Impl : internal::HandleBlock {
  Impl(uv_loop_t* loop, bool unix) : unix_socket(unix) {
    LOOP_CHECK((unix ? uv_pipe_init(loop, &pipe, 0) : uv_tcp_init(loop, &tcp)) == 0);
    Adopt(&tcp);  // a union: the same address whichever member is live
    LOOP_CHECK(uv_timer_init(loop, &timer) == 0);
    Adopt(&timer);
  }

  uv_stream_t* stream() { return reinterpret_cast<uv_stream_t*>(&tcp); }

  void CloseWith(std::string why) {
    if (state() != HandleState::kOpen) return;
    reason = std::move(why);
    BeginClose();
  }

  void OnClosed(bool owner_alive) override {
    if (!owner_alive || !on_close) return;
    OnClose callback = std::move(on_close);
    callback(reason);
  }

  void StartReading() {
    if (reading) return;
    if (int rc = uv_read_start(stream(), &OnAlloc, &OnRead); rc < 0) {
      CloseWith(UvErrorText("read from " + peer, rc));
      return;
    }
    reading = true;
  }

  void RestartIdleTimer() {
    if (flushing || state() != HandleState::kOpen) return;
    if (options.read_idle_timeout.count() > 0) {
      uv_timer_start(&timer, &OnTimer, static_cast<uint64_t>(options.read_idle_timeout.count()), 0);
    } else {
      uv_timer_stop(&timer);
    }
  }

  Status Write(std::vector<uint8_t>&& bytes, bool has_prefix) {
    internal::CheckLoopThread(timer.loop);
    if (state() != HandleState::kOpen || flushing)
      return Error{"connection to " + peer + " is closed"};
    if (has_prefix && (bytes.size() < kFramePrefixBytes ||
                       ReadFramePrefix(bytes.data()) != bytes.size() - kFramePrefixBytes)) {
      return Error{"SendPrefixed: the length prefix does not match the frame's size"};
    }
    const size_t payload = has_prefix ? bytes.size() - kFramePrefixBytes : bytes.size();
    if (payload > options.max_frame_bytes) {
      return Error{"frame of " + std::to_string(payload) + " bytes exceeds the limit of " +
                   std::to_string(options.max_frame_bytes) + " bytes"};
    }
    auto* request = new WriteRequest;
    request->req.data = request;
    request->bytes = std::move(bytes);
    std::array<uv_buf_t, 2> bufs;
    unsigned count = 0;
    if (!has_prefix) {
      WriteFramePrefix(static_cast<uint32_t>(payload), request->prefix.data());
      bufs[count++] =
          uv_buf_init(reinterpret_cast<char*>(request->prefix.data()), kFramePrefixBytes);
    }
    if (!request->bytes.empty()) {
      bufs[count++] = uv_buf_init(reinterpret_cast<char*>(request->bytes.data()),
                                  static_cast<unsigned>(request->bytes.size()));
    }
    if (int rc = uv_write(&request->req, stream(), bufs.data(), count, &OnWrite); rc < 0) {
      delete request;
      std::string why = UvErrorText("write to " + peer, rc);
      CloseWith(why);
      return Error{why};
    }
    // libuv wrote what the kernel took; the rest waits in its queue for a peer that reads.
    if (const size_t queued = uv_stream_get_write_queue_size(stream());
        queued > options.max_queued_bytes) {
      std::string why = "send queue full: " + std::to_string(queued) +
                        " bytes waiting for the peer to read (limit " +
                        std::to_string(options.max_queued_bytes) + ")";
      CloseWith(why);
      return Error{why};
    }
    return Ok{};
  }

  static void OnAlloc(uv_handle_t*, size_t, uv_buf_t* buf) noexcept {
    *buf = uv_buf_init(ThreadReadBuffer(), kReadBufferBytes);
  }

  static void OnRead(uv_stream_t* stream, ssize_t n, const uv_buf_t* buf) noexcept {
    Impl* impl = Of<Impl>(stream);
    if (n == 0) return;
    if (n < 0) {
      if (impl->flushing) {
        impl->CloseWith(impl->flush_reason);
      } else if (n == UV_EOF) {
        impl->CloseWith(kPeerClosedReason);
      } else {
        impl->CloseWith(UvErrorText("read from " + impl->peer, static_cast<int>(n)));
      }
      return;
    }
    impl->bytes_received += static_cast<uint64_t>(n);
    if (impl->flushing) return;  // closing: what the peer still sends is dropped
    impl->RestartIdleTimer();
    const std::span<const uint8_t> bytes(reinterpret_cast<const uint8_t*>(buf->base),
                                         static_cast<size_t>(n));
    const Status status = impl->splitter->Feed(bytes, [impl](std::span<const uint8_t> payload) {
      ++impl->frames_received;
      if (impl->on_frame) impl->on_frame(payload);
      return impl->state() == HandleState::kOpen && !impl->flushing;
    });
    if (!status.ok()) impl->CloseWith(status.error());
  }

  static void OnWrite(uv_write_t* req, int status) noexcept {
    Impl* impl = Of<Impl>(req->handle);  // write callbacks run before the close callback
    delete static_cast<WriteRequest*>(req->data);
    if (status < 0 && status != UV_ECANCELED) {
      impl->CloseWith(UvErrorText("write to " + impl->peer, status));
    }
  }

  static void OnTimer(uv_timer_t* timer) noexcept {
    Impl* impl = Of<Impl>(timer);
    if (impl->flushing) {
      impl->CloseWith(impl->flush_reason + " (the peer did not close within " +
                      Millis(impl->options.flush_timeout) + ")");
    } else {
      impl->CloseWith("no data for " + Millis(impl->options.read_idle_timeout) +
                      " (read idle timeout)");
    }
  }

  static void OnConnect(uv_connect_t* req, int status) noexcept {
    Impl* impl = Of<Impl>(req->handle);
    impl->connecting = false;
    if (status == UV_ECANCELED) return;  // closed while connecting
    if (status < 0) {
      impl->CloseWith(UvErrorText("connect to " + impl->peer, status));
      return;
    }
    if (!impl->unix_socket) uv_tcp_nodelay(&impl->tcp, 1);
    impl->StartReading();
    if (impl->on_connected && impl->state() == HandleState::kOpen) {
      std::function<void()> callback = std::move(impl->on_connected);
      callback();  // last: it may destroy the connection
    }
  }

  // Our side is flushed and FIN sent; OnRead closes when the peer's EOF answers it.
  static void OnShutdown(uv_shutdown_t*, int) noexcept {}

  union {
    uv_tcp_t tcp;
    uv_pipe_t pipe;
  };
  uv_timer_t timer;  // read-idle timeout, then the flush deadline
  uv_connect_t connect_req;
  uv_shutdown_t shutdown_req;
  const bool unix_socket;

  ConnectionOptions options;
  std::unique_ptr<FrameSplitter> splitter;
  OnFrame on_frame;
  OnClose on_close;
  std::function<void()> on_connected;
  std::string peer;
  std::string reason;        // given to on_close
  std::string flush_reason;  // CloseAfterFlush's
  bool started = false;
  bool connecting = false;
  bool reading = false;
  bool flushing = false;
  uint64_t bytes_received = 0;
  uint64_t frames_received = 0;
};

Result<std::unique_ptr<FramedConnection>> FramedConnection::ConnectTcp(
    EventLoop& loop, const SocketAddress& address, const ConnectionOptions& options,
    OnFrame on_frame, OnClose on_close, std::function<void()> on_connected) {
  internal::CheckLoopThread(loop.uv());
  std::unique_ptr<FramedConnection> connection(new FramedConnection);
  auto* impl = new Impl(loop.uv(), /*unix=*/false);
  connection->block_.Reset(impl);
  connection->peer_ = impl->peer = address.ToString();
  if (int rc = uv_tcp_connect(&impl->connect_req, &impl->tcp, address.get(), &Impl::OnConnect);
      rc < 0) {
    return UvError("connect to " + impl->peer, rc);  // the wrapper's destruction closes the block
  }
  impl->connecting = true;
  impl->on_connected = std::move(on_connected);
  connection->Start(options, std::move(on_frame), std::move(on_close));
  return connection;
}

Result<std::unique_ptr<FramedConnection>> FramedConnection::ConnectUnix(
    EventLoop& loop, const std::string& path, const ConnectionOptions& options, OnFrame on_frame,
    OnClose on_close, std::function<void()> on_connected) {
  internal::CheckLoopThread(loop.uv());
  if (path.empty() || path.size() >= sizeof(sockaddr_un{}.sun_path)) {
    return Error{"unix socket path '" + path + "': must be 1 to " +
                 std::to_string(sizeof(sockaddr_un{}.sun_path) - 1) + " bytes"};
  }
  std::unique_ptr<FramedConnection> connection(new FramedConnection);
  auto* impl = new Impl(loop.uv(), /*unix=*/true);
  connection->block_.Reset(impl);
  connection->peer_ = impl->peer = "unix:" + path;
  uv_pipe_connect(&impl->connect_req, &impl->pipe, path.c_str(), &Impl::OnConnect);
  impl->connecting = true;
  impl->on_connected = std::move(on_connected);
  connection->Start(options, std::move(on_frame), std::move(on_close));
  return connection;
}

Result<std::unique_ptr<FramedConnection>> FramedConnection::Accept(
    uv_stream_t* server, bool unix_socket, const std::string& listener_name) {
  std::unique_ptr<FramedConnection> connection(new FramedConnection);
  auto* impl = new Impl(server->loop, unix_socket);
  connection->block_.Reset(impl);
  if (int rc = uv_accept(server, impl->stream()); rc < 0) {
    return UvError("accept on " + listener_name, rc);
  }
  uv_os_fd_t fd = -1;
  if (uv_fileno(reinterpret_cast<uv_handle_t*>(impl->stream()), &fd) == 0) {
    if (Status room = CheckDescriptorRoom(fd); !room.ok()) {
      return Error{"accept on " + listener_name + ": " + room.error()};
    }
  }
  if (unix_socket) {
    std::string peer = "unix:" + listener_name;
    uv_os_fd_t fd;
    ucred credentials{};
    socklen_t length = sizeof credentials;
    if (uv_fileno(reinterpret_cast<uv_handle_t*>(&impl->pipe), &fd) == 0 &&
        getsockopt(fd, SOL_SOCKET, SO_PEERCRED, &credentials, &length) == 0) {
      peer += " (pid " + std::to_string(credentials.pid) + " uid " +
              std::to_string(credentials.uid) + ")";
    }
    impl->peer = std::move(peer);
  } else {
    uv_tcp_nodelay(&impl->tcp, 1);  // frames are small and latency-bound (heartbeats, leases)
    sockaddr_storage address{};
    int length = sizeof address;
    Result<SocketAddress> peer = Error{"unknown"};
    if (uv_tcp_getpeername(&impl->tcp, reinterpret_cast<sockaddr*>(&address), &length) == 0) {
      peer = SocketAddress::FromSockaddr(reinterpret_cast<sockaddr*>(&address));
    }
    impl->peer = peer.ok() ? peer->ToString() : "unknown peer";
  }
  connection->peer_ = impl->peer;
  return connection;
}

void FramedConnection::Start(const ConnectionOptions& options, OnFrame on_frame, OnClose on_close) {
  Impl* impl = block_.get();
  LOOP_CHECK(impl != nullptr && !impl->started);
  internal::CheckLoopThread(impl->timer.loop);
  impl->started = true;
  impl->options = options;
  impl->splitter = std::make_unique<FrameSplitter>(options.max_frame_bytes, options.frame_budget);
  // Another connection's frame needed the budget this one held the most of.
  impl->splitter->set_on_evicted([impl](const std::string& reason) { impl->CloseWith(reason); });
  impl->on_frame = std::move(on_frame);
  impl->on_close = std::move(on_close);
  if (!impl->connecting) impl->StartReading();
  impl->RestartIdleTimer();
}

Status FramedConnection::Send(std::span<const uint8_t> payload) {
  return Write(std::vector<uint8_t>(payload.begin(), payload.end()), false);
}

Status FramedConnection::Send(std::vector<uint8_t>&& payload) {
  return Write(std::move(payload), false);
}

Status FramedConnection::SendPrefixed(std::vector<uint8_t>&& frame) {
  return Write(std::move(frame), true);
}

Status FramedConnection::Write(std::vector<uint8_t>&& bytes, bool has_prefix) {
  if (!block_.open()) return Error{"connection to " + peer_ + " is closed"};
  return block_->Write(std::move(bytes), has_prefix);
}

void FramedConnection::Close(const std::string& reason) {
  if (block_.open()) block_->CloseWith(reason);
}

void FramedConnection::CloseAfterFlush(const std::string& reason) {
  Impl* impl = block_.get();
  if (impl == nullptr || impl->state() != HandleState::kOpen || impl->flushing) return;
  internal::CheckLoopThread(impl->timer.loop);
  if (impl->connecting) {
    impl->CloseWith(reason);  // nothing was sent yet
    return;
  }
  if (int rc = uv_shutdown(&impl->shutdown_req, impl->stream(), &Impl::OnShutdown); rc < 0) {
    impl->CloseWith(reason);
    return;
  }
  impl->flushing = true;
  impl->flush_reason = reason;
  // Keep reading (and dropping) until the peer's EOF: closing with unread input would send a
  // reset that can destroy the frames we just flushed before the peer reads them.
  impl->StartReading();
  uv_timer_start(&impl->timer, &Impl::OnTimer,
                 static_cast<uint64_t>(impl->options.flush_timeout.count()), 0);
}

void FramedConnection::SetReadIdleTimeout(std::chrono::milliseconds timeout) {
  Impl* impl = block_.get();
  if (impl == nullptr) return;
  impl->options.read_idle_timeout = timeout;
  if (impl->started) impl->RestartIdleTimer();
}

HandleState FramedConnection::state() const {
  const HandleState state = block_.state();
  if (state == HandleState::kOpen && block_->flushing) return HandleState::kClosing;
  return state;
}

size_t FramedConnection::queued_bytes() const {
  return block_.open() ? uv_stream_get_write_queue_size(block_->stream()) : 0;
}

uint64_t FramedConnection::bytes_received() const {
  return block_.get() ? block_->bytes_received : 0;
}

uint64_t FramedConnection::frames_received() const {
  return block_.get() ? block_->frames_received : 0;
}

void FramedConnection::SetMaxReceiveFrameBytes(uint32_t max_frame_bytes) {
  Impl* impl = block_.get();
  if (impl == nullptr || !impl->splitter) return;
  internal::CheckLoopThread(impl->timer.loop);
  impl->splitter->set_max_payload_bytes(max_frame_bytes);
}

}  // namespace radfarm::loop
