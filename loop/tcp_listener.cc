#include "loop/tcp_listener.h"

#include "base/result.h"
#include "loop/listen_block.h"
#include "loop/socket_address.h"
#include "loop/uv_error.h"

namespace radfarm::loop {

Result<std::unique_ptr<TcpListener>> TcpListener::Listen(EventLoop& loop, const HostPort& address,
                                                         OnConnection on_connection) {
  internal::CheckLoopThread(loop.uv());
  Result<std::vector<SocketAddress>> resolved = Resolve(address, /*passive=*/true);
  if (!resolved.ok()) return Error{"listen on " + resolved.error()};
  const SocketAddress& bind_address = resolved->front();

  std::unique_ptr<TcpListener> listener(new TcpListener);
  auto* block = new internal::ListenBlock(loop.uv(), /*unix=*/false, std::move(on_connection));
  listener->block_.Reset(block);
  block->name = address.ToString();
  if (int rc = uv_tcp_bind(&block->tcp, bind_address.get(), 0); rc < 0) {
    return UvError("listen on " + block->name, rc);
  }
  RADFARM_RETURN_IF_ERROR(block->Listen());

  sockaddr_storage bound{};
  int length = sizeof bound;
  if (int rc = uv_tcp_getsockname(&block->tcp, reinterpret_cast<sockaddr*>(&bound), &length);
      rc < 0) {
    return UvError("listen on " + block->name + ": getsockname", rc);
  }
  Result<SocketAddress> actual = SocketAddress::FromSockaddr(reinterpret_cast<sockaddr*>(&bound));
  if (!actual.ok()) return Error{"listen on " + block->name + ": " + actual.error()};
  listener->address_ = block->name = actual->ToString();
  listener->port_ = actual->port();
  return listener;
}

void TcpListener::Close() {
  if (block_.open()) block_->BeginClose();
}

HandleState TcpListener::state() const { return block_.state(); }

}  // namespace radfarm::loop
