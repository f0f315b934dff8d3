#include "loop/host_port.h"

namespace radfarm::loop {
namespace {

Error Expected(std::string_view text, std::string_view what, std::string_view detail) {
  std::string message(what);
  message += ": expected HOST:PORT, got '";
  message += text;
  message += "' (";
  message += detail;
  message += ")";
  return Error{std::move(message)};
}

bool ParsePort(std::string_view digits, uint16_t* port) {
  if (digits.empty() || digits.size() > 5) return false;
  uint32_t value = 0;
  for (char c : digits) {
    if (c < '0' || c > '9') return false;
    value = value * 10 + static_cast<uint32_t>(c - '0');
  }
  if (value > 65535) return false;
  *port = static_cast<uint16_t>(value);
  return true;
}

}  // namespace

std::string HostPort::ToString() const {
  const std::string port_text = std::to_string(port);
  if (host.find(':') != std::string::npos) return "[" + host + "]:" + port_text;
  return host + ":" + port_text;
}

Result<HostPort> ParseHostPort(std::string_view text, std::string_view what) {
  std::string_view host;
  std::string_view port;
  if (!text.empty() && text.front() == '[') {
    const size_t close = text.find(']');
    if (close == std::string_view::npos) return Expected(text, what, "missing ']'");
    if (close + 1 >= text.size() || text[close + 1] != ':') {
      return Expected(text, what, "missing ':PORT' after ']'");
    }
    host = text.substr(1, close - 1);
    port = text.substr(close + 2);
  } else {
    const size_t colon = text.rfind(':');
    if (colon == std::string_view::npos) return Expected(text, what, "missing ':PORT'");
    host = text.substr(0, colon);
    port = text.substr(colon + 1);
    if (host.find(':') != std::string_view::npos) {
      return Expected(text, what, "an IPv6 host needs brackets, as in [::1]:7000");
    }
  }
  if (host.empty()) return Expected(text, what, "empty host; use 0.0.0.0 or [::] for all");
  for (char c : host) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte <= 0x20 || byte >= 0x7f || c == '[' || c == ']' || c == '/') {
      return Expected(text, what, "the host has a character not allowed in a name or address");
    }
  }
  HostPort result;
  if (!ParsePort(port, &result.port)) {
    return Expected(text, what, "the port must be a number from 0 to 65535");
  }
  result.host = std::string(host);
  return result;
}

}  // namespace radfarm::loop
