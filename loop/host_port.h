// "HOST:PORT" strings, as given on the command line (--listen, --master) and written to
// STATE/listen.addr. IPv6 hosts are bracketed: "[::1]:7000". Port 0 asks the OS for a free port.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "base/result.h"

namespace radfarm::loop {

struct HostPort {
  std::string host;  // no brackets
  uint16_t port = 0;

  // "host:port", with brackets if host contains ':'.
  std::string ToString() const;
};

// Errors read "WHAT: expected HOST:PORT, got 'TEXT' (detail)", where WHAT names the source, for
// example the flag "--listen".
Result<HostPort> ParseHostPort(std::string_view text, std::string_view what);

}  // namespace radfarm::loop
