// TcpListener: a listening TCP socket on "HOST:PORT" (IPv4 or IPv6; port 0 picks a free port).
// Each accepted connection arrives on the loop thread as a FramedConnection that is not yet
// reading: the callback takes ownership and calls Start(). Loop thread only.
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "base/result.h"
#include "loop/event_loop.h"
#include "loop/framed_connection.h"
#include "loop/handle_block.h"
#include "loop/host_port.h"

namespace radfarm::loop {

namespace internal {
struct ListenBlock;
}

class TcpListener {
 public:
  using OnConnection = std::function<void(std::unique_ptr<FramedConnection>)>;

  // Binds and listens. A host name (not an IP literal) is resolved first, which blocks: this is
  // for start-up. Errors name the address: "listen on 127.0.0.1:7000: address already in use".
  static Result<std::unique_ptr<TcpListener>> Listen(EventLoop& loop, const HostPort& address,
                                                     OnConnection on_connection);
  TcpListener(const TcpListener&) = delete;
  TcpListener& operator=(const TcpListener&) = delete;

  // The bound address (uv_tcp_getsockname), port filled in: "127.0.0.1:40123", "[::1]:40123".
  // What the master writes to STATE/listen.addr.
  const std::string& address() const { return address_; }
  uint16_t port() const { return port_; }

  void Close();
  HandleState state() const;

 private:
  TcpListener() = default;
  internal::BlockRef<internal::ListenBlock> block_;
  std::string address_;
  uint16_t port_ = 0;
};

}  // namespace radfarm::loop
