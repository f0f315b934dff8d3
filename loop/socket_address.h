// SocketAddress: an IPv4 or IPv6 address and port (a sockaddr_storage), printed as "HOST:PORT".
#pragma once

#include <sys/socket.h>

#include <cstdint>
#include <string>
#include <vector>

#include "base/result.h"
#include "loop/host_port.h"

namespace radfarm::loop {

class SocketAddress {
 public:
  // The host must be an IP literal ("127.0.0.1", "::1"); no name lookup.
  static Result<SocketAddress> FromIpLiteral(const HostPort& host_port);
  // AF_INET or AF_INET6 only.
  static Result<SocketAddress> FromSockaddr(const sockaddr* address);

  const sockaddr* get() const { return reinterpret_cast<const sockaddr*>(&storage_); }
  int family() const { return storage_.ss_family; }
  uint16_t port() const;
  // "127.0.0.1:7000", "[::1]:7000".
  std::string ToString() const;

 private:
  SocketAddress() = default;
  sockaddr_storage storage_{};
};

// IP literals directly; names through getaddrinfo, which BLOCKS: call it at start-up or on a
// WorkQueue, never from a loop callback. `passive`: addresses to bind rather than to connect to.
// A name may give several addresses ("localhost": ::1 and 127.0.0.1): try them in order.
Result<std::vector<SocketAddress>> Resolve(const HostPort& host_port, bool passive);

}  // namespace radfarm::loop
