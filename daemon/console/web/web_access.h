// WebAccess: who may read the status page and who may act on jobs (docs/OPERATIONS.md).
//
//   bound to loopback, no token:   anyone on this machine reads; nobody acts (read-only page)
//   bound to loopback, a token:    anyone on this machine reads; acting needs the token
//   bound elsewhere (needs token): reading and acting need the token
//
// The token is sent as "Authorization: Bearer TOKEN" (scripts, Prometheus) or traded on the
// page for a session of its own (session_table.h), sent the same way. No credential rides in a
// cookie: a browser hands cookies to every port of a host, so a page served by another program on
// this machine could replay one. On loopback the Host header must name a loopback address: a name
// that an attacker's DNS points at 127.0.0.1 (DNS rebinding) is refused.
//
// Immutable after construction: any thread.
#pragma once

#include <string>
#include <string_view>

#include "base/result.h"

namespace radfarm::web {

// "127.0.0.1", "127.x.y.z", "::1", "localhost" (no port, no brackets).
bool IsLoopbackHost(std::string_view host);

// Reads a token file: one line of at least 16 characters, no spaces inside; surrounding
// whitespace is ignored. Errors name the file.
Result<std::string> ReadTokenFile(const std::string& path);

class WebAccess {
 public:
  // `token` empty: no token (loopback only; CheckMasterConfig enforces it).
  WebAccess(bool loopback, std::string token);

  bool loopback() const { return loopback_; }
  bool has_token() const { return !token_.empty(); }
  // Loopback binding: the Host header (perhaps with ":port", IPv6 bracketed) names a loopback
  // address, or is absent. Elsewhere: always true (the token guards).
  bool HostAllowed(std::string_view host_header) const;
  // Whether the Authorization header holds the token (constant time).
  bool BearerValid(std::string_view authorization) const;
  // What follows "Bearer " in an Authorization header, trimmed; "" for any other header.
  static std::string_view BearerOf(std::string_view authorization);
  // Whether `token` is the token (constant time); false when there is none.
  bool TokenMatches(std::string_view token) const;

  bool MayRead(bool authenticated) const { return loopback_ || authenticated; }
  bool MayAct(bool authenticated) const { return has_token() && authenticated; }

 private:
  bool loopback_;
  std::string token_;
};

}  // namespace radfarm::web
