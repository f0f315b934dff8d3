#include "loop/socket_address.h"

#include <netdb.h>
#include <netinet/in.h>
#include <uv.h>

#include <cstring>

namespace radfarm::loop {

Result<SocketAddress> SocketAddress::FromIpLiteral(const HostPort& host_port) {
  SocketAddress address;
  auto* v4 = reinterpret_cast<sockaddr_in*>(&address.storage_);
  auto* v6 = reinterpret_cast<sockaddr_in6*>(&address.storage_);
  if (uv_ip4_addr(host_port.host.c_str(), host_port.port, v4) == 0) return address;
  address.storage_ = {};
  if (uv_ip6_addr(host_port.host.c_str(), host_port.port, v6) == 0) return address;
  return Error{host_port.ToString() + ": '" + host_port.host + "' is not an IP address"};
}

Result<SocketAddress> SocketAddress::FromSockaddr(const sockaddr* source) {
  SocketAddress address;
  if (source->sa_family == AF_INET) {
    std::memcpy(&address.storage_, source, sizeof(sockaddr_in));
  } else if (source->sa_family == AF_INET6) {
    std::memcpy(&address.storage_, source, sizeof(sockaddr_in6));
  } else {
    return Error{"address family " + std::to_string(source->sa_family) + " is not IPv4 or IPv6"};
  }
  return address;
}

uint16_t SocketAddress::port() const {
  if (family() == AF_INET6) return ntohs(reinterpret_cast<const sockaddr_in6*>(get())->sin6_port);
  return ntohs(reinterpret_cast<const sockaddr_in*>(get())->sin_port);
}

std::string SocketAddress::ToString() const {
  char host[INET6_ADDRSTRLEN] = "?";
  if (family() == AF_INET6) {
    uv_ip6_name(reinterpret_cast<const sockaddr_in6*>(get()), host, sizeof host);
  } else {
    uv_ip4_name(reinterpret_cast<const sockaddr_in*>(get()), host, sizeof host);
  }
  return HostPort{host, port()}.ToString();
}

Result<std::vector<SocketAddress>> Resolve(const HostPort& host_port, bool passive) {
  if (Result<SocketAddress> literal = SocketAddress::FromIpLiteral(host_port); literal.ok()) {
    return std::vector<SocketAddress>{*literal};
  }
  addrinfo hints{};
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_STREAM;
  hints.ai_flags = passive ? AI_PASSIVE : 0;
  addrinfo* found = nullptr;
  const std::string port = std::to_string(host_port.port);
  if (int rc = getaddrinfo(host_port.host.c_str(), port.c_str(), &hints, &found); rc != 0) {
    return Error{host_port.ToString() + ": cannot resolve '" + host_port.host +
                 "': " + gai_strerror(rc)};
  }
  std::vector<SocketAddress> addresses;
  for (const addrinfo* info = found; info != nullptr; info = info->ai_next) {
    if (Result<SocketAddress> address = SocketAddress::FromSockaddr(info->ai_addr); address.ok()) {
      addresses.push_back(*address);
    }
  }
  freeaddrinfo(found);
  if (addresses.empty()) return Error{host_port.ToString() + ": no IPv4 or IPv6 address"};
  return addresses;
}

}  // namespace radfarm::loop
