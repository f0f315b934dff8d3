// A minimal HTTP/1.0 client for tests of radfarmd's web console: one request per connection, the
// body read until the server closes. Blocking, loopback only in practice; every read has a
// deadline, so a server that hangs fails the test instead of hanging it.
#pragma once

#include <chrono>
#include <map>
#include <string>
#include <vector>

#include "base/result.h"

namespace radfarm::testing {

struct HttpResponse {
  int status = 0;
  std::map<std::string, std::string> headers;  // names in lower case
  std::string body;
};

// `address` "HOST:PORT" (IP literal). `headers` are "Name: value" lines; a Host header naming
// `address` is sent unless one is given.
Result<HttpResponse> HttpRequest(const std::string& address, const std::string& method,
                                 const std::string& path,
                                 const std::vector<std::string>& headers = {},
                                 const std::string& body = "",
                                 std::chrono::milliseconds timeout = std::chrono::seconds(60));

// GETs `path` and reads until the raw response (headers and body) contains `marker`, then closes:
// for streams that never end (server-sent events). Returns what was read.
Result<std::string> HttpReadUntil(const std::string& address, const std::string& path,
                                  const std::string& marker, std::chrono::milliseconds timeout);

}  // namespace radfarm::testing
